#pragma once
// The morph's animatable tracks (project/morph_setup.h) as addressed tracks for
// the key edits of anim/key_edit.h, and the undoable commands that edit them.
// Addresses: node = kMorphTracksNode with param = MorphTrack (easing, blend,
// noise amplitude); or node = MorphSlot (0 source, 1 target), point = the
// stand-in segment index, param = SegmentChannel. Every morph track runs
// over a normalised progress u in [0, 1]: easing over a transition (A->B,
// C->D), the others over the morph (B->C); key times stay in [0, 1].
#include <memory>
#include <string>
#include <vector>

#include "core/anim/key_edit.h"
#include "core/doc/command.h"
#include "core/project/project.h"
#include "core/util/result.h"

namespace animorph {

constexpr int kMorphTracksNode = -1;
enum class MorphTrack { Easing = 0, Blend = 1, NoiseAmplitude = 2 };
enum class MorphSlot { Source = 0, Target = 1 };
enum class SegmentChannel { AOffset = 0, BOffset = 1, RadiusScale = 2 };

ParamAddress morphTrackAddress(MorphTrack t);
ParamAddress segmentTrackAddress(MorphSlot slot, int segment, SegmentChannel c);
// True for the easing track (x: a transition's progress), false for tracks over the morph's progress.
bool overTransition(const ParamAddress& a);

// The actor morph of slot (by the morph's source / target id), or null.
ActorMorph* slotActor(MorphSetup& m, MorphSlot slot);
const ActorMorph* slotActor(const MorphSetup& m, MorphSlot slot);
// The keyed tracks of one stand-in segment, or null when it has none.
SegmentTracks* findSegmentTracks(ActorMorph& a, int segment);
const SegmentTracks* findSegmentTracks(const ActorMorph& a, int segment);

// The track at a, or monostate (no such actor, or the segment has no tracks).
TrackPtr findMorphTrack(MorphSetup& m, const ParamAddress& a);
ConstTrackPtr findMorphTrack(const MorphSetup& m, const ParamAddress& a);
// "blend w(u)", "source segment 3 radius scale", ...
std::string morphTrackName(const ParamAddress& a);
// The morph's tracks as a TrackSet (keys in [0, 1]; radius scales >= 0). Refers to m.
TrackSet morphTrackSet(MorphSetup& m);

// Every track of the morph that exists now: easing, blend, noise amplitude,
// then the keyed segment tracks of source and target (by segment).
std::vector<ParamAddress> morphTrackAddresses(const MorphSetup& m);

// The morph's progress u at a timeline frame (0 before B, 1 after C), and the
// transition's progress (A->B or C->D; negative outside the transitions).
double morphProgressAt(const MorphSetup& m, double frame);
double transitionProgressAt(const MorphSetup& m, double frame);

// Replaces the morph's tracks (easing, blend, noise amplitude and every
// actor's segment tracks) with after's; nothing else of the morph changes
// (a stand-in or weight-map edit made meanwhile stays). Commands with the same
// non-empty mergeKey fold into one undo step during a drag.
std::unique_ptr<Command> setMorphTracksCommand(const Project& p, const MorphSetup& after, std::string label,
                                               std::string mergeKey = {});
// Runs edit on a copy of the project's morph (or of from, the morph when a
// drag began); the command on success, the edit's error otherwise.
template <class Edit>
Result<std::unique_ptr<Command>> editMorphTracks(const Project& p, std::string label, Edit&& edit,
                                                 std::string mergeKey = {}, const MorphSetup* from = nullptr) {
  if (!p.morph.enabled()) return Error{"the project has no morph"};
  MorphSetup copy = from ? *from : p.morph;
  Status s = edit(copy);
  if (!s) return Error{s.error()};
  return setMorphTracksCommand(p, copy, std::move(label), std::move(mergeKey));
}

// Sets (key = false: like typing in a field; key = true: the key button) the
// value of a segment's track at progress u, creating the segment's
// SegmentTracks entry (neutral: zero offsets, scale 1) when it has none.
// Refuses an unknown slot or segment and non-finite values.
Result<std::unique_ptr<Command>> setSegmentTrackCommand(const Project& p, MorphSlot slot, int segment,
                                                        SegmentChannel c, double u, const ParamSample& value,
                                                        bool key, std::string mergeKey = {});
// Removes a segment's keyed tracks (it then follows its stand-in unchanged).
Result<std::unique_ptr<Command>> removeSegmentTracksCommand(const Project& p, MorphSlot slot, int segment);

// Easing shapes for the preset buttons, over u in [0, 1] from 0 to 1.
enum class EasingPreset { Linear, Smoothstep, EaseIn, EaseOut };
FloatTrack easingPresetTrack(EasingPreset p);
const char* easingPresetName(EasingPreset p);  // "linear", "smoothstep", "ease-in", "ease-out"

}  // namespace animorph
