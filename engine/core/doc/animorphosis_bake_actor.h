#pragma once
// Animorphosis > Bake to Key-frame Actor (docs/animorphosis.md): the project's
// animorphosis baked by bakeKeyframes (animorphosis/bake_keys.h) into a plain
// key-framed BlobTree, held by a new BlobTree actor that can be edited further
// like any other. The actor is named after the two trees ("Source -> Target
// (keys)"), plays on the timeline's clock (offset 0, speed 1, no loop: the
// tree holds C(t0) before the interval and C(t1) after it) and stands where C
// does at the middle of the interval (the source and target transforms
// blended by the global s there). Baking works on a copy of the project, so it
// can run off the UI thread; adding the actor is one undoable step.
#include <memory>
#include <string>

#include "core/animorphosis/bake_keys.h"
#include "core/doc/command.h"
#include "core/util/result.h"

namespace animorph {

struct BakedActor {
  Actor actor;            // kind BlobTree; its id unique in the project it was baked from
  BakeKeysReport report;  // key counts and the largest deviation from the live C
};

// Needs a valid animorphosis (checkAnimorphosis); its error otherwise. settings' progress is
// called per node of C; when settings.cancel turns true the bake stops within one channel and
// returns jobCancelled() (util/job_progress.h). p is never changed.
Result<BakedActor> bakeAnimorphosisActor(const Project& p, const BakeKeysSettings& settings = {});

// Adds the baked actor to p (its id made unique again: the project may have
// changed while the bake ran). Undo removes it.
std::unique_ptr<Command> addBakedActorCommand(const Project& p, BakedActor baked);

// "Baked Walker -> Flyer (keys): 412 channels, 2,310 keys, at most 9 on one
// channel (nA + nB + ns = 11); largest deviation from the live animorphosis 0.0012 (node 7 radius)".
std::string describeBakedActor(const BakedActor& baked);

}  // namespace animorph
