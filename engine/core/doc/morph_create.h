#pragma once
// Setting up a project's morph between any two of its actors (Create > Morph...,
// the inspector's source / target, animorph-cli new): a skinned glTF character
// or a BlobTree actor on either side. A glTF side keeps the stand-in the
// project has for it, or gets one fitted; a BlobTree side is its own stand-in
// (no transition: A = B on a BlobTree source, C = D on a BlobTree target).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/project/asset_cache.h"
#include "core/doc/command.h"
#include "core/project/project.h"
#include "core/standin_morph/target_alignment.h"
#include "core/util/result.h"

namespace animorph {

struct MorphChoice {
  std::string sourceActorId, targetActorId;
  MorphMethod method = MorphMethod::Interpolation;
  MorphMarkers markers;
};

// The project's morph with choice applied (the rest of the setup, e.g. easing
// and projection, kept; the chain pairs kept for the same two actors, reversed
// when they swap sides, dropped for other actors). baseDir resolves glTF asset paths; messages (may be
// null) receive one line per stand-in fitted. Errors name the actor and the
// reason: unknown id, source = target, markers out of order, an asset that
// does not load, a stand-in that cannot be fitted.
Result<MorphSetup> proposeMorph(const Project& p, const std::string& baseDir, AssetCache& assets,
                                const MorphChoice& choice, std::vector<std::string>* messages = nullptr);

// How Create > Morph... would align the target actor to the source actor (both glTF
// characters that load): the alignment relative to the source's frame and the target actor's
// transform with it applied (the source actor's transform composed in). nullopt when a side is
// a BlobTree or does not load.
struct ActorAlignment {
  TargetAlignment alignment;
  Transform targetTransform;
};
std::optional<ActorAlignment> proposeTargetAlignment(const Project& p, const std::string& baseDir, AssetCache& assets,
                                                     const std::string& sourceId, const std::string& targetId);

// Sets the project's morph and, when targetTransform is given, the target actor's transform:
// one undo step.
std::unique_ptr<Command> createMorphCommand(const Project& p, MorphSetup after, const std::optional<Transform>& targetTransform,
                                            std::string label);

// Markers collapsed where a side is a BlobTree (A onto B, D onto C).
MorphMarkers collapseTreeMarkers(const Project& p, const MorphChoice& choice);

// Replaces the project's whole morph section (one undo step).
std::unique_ptr<Command> setMorphCommand(const Project& p, MorphSetup after, std::string label);

// The inspector's swap: source and target exchanged, markers mirrored inside
// [A, D] so that the transition lengths follow their actors; the stand-ins
// and tracks stay with their actors, chain pairs are reversed (swappedChainPairs).
std::unique_ptr<Command> swapMorphSidesCommand(const Project& p);

}  // namespace animorph
