#pragma once
// The morph of a project (docs/design.md §5): which actor morphs into which, the
// four timeline markers, the implicit method and its parameters, the easing
// and blend tracks, and per actor its stand-in, weight map and keyed
// stand-in edits. Plain data, saved as the project's "morph" section.
#include <string>
#include <vector>

#include "core/anim/track.h"
#include "core/standin_morph/chain_pair.h"
#include "core/standin_morph/morph_field.h"
#include "core/standin/standin.h"

namespace animorph {

// Frames of the four markers: before A the source plays; A->B it collapses
// onto its stand-in; B->C the implicit morph; C->D the target expands from its
// stand-in; after D the target plays. A <= B <= C <= D.
struct MorphMarkers {
  int a = 24, b = 48, c = 84, d = 108;
  bool operator==(const MorphMarkers&) const = default;
};

// User-controlled morphing of one stand-in segment, keyed over the morph's
// progress u in [0, 1] (B -> C). Neutral values (zero offsets, scale 1) at
// u = 0 and 1 keep the morph continuous with the transitions.
struct SegmentTracks {
  int segment = 0;                   // index into the actor's stand-in segments
  Vec3Track aOffset{glm::vec3(0.0f)};  // added to the start, in the segment node's space (m)
  Vec3Track bOffset{glm::vec3(0.0f)};  // added to the end
  FloatTrack radiusScale{1.0f};      // multiplies the radius; below 0.25 the segment also fades out (0: gone)
};

struct ActorMorph {
  std::string actorId;
  Standin standin;
  std::vector<float> weightMap;  // per vertex over Character::meshNodes(), in [0, 1]; empty: none
  std::vector<SegmentTracks> segmentTracks;
};

// How vertices are bound to the stand-in (projection) and pulled back onto it
// near the end of a transition.
struct MorphProjection {
  bool atClipTime = false;    // false: rest pose; true: the actor's clip at clipTimeSec
  double clipTimeSec = 0.0;
  int maxIterations = 40;
  float tolerance = 1e-5f;
  float maxStepRadii = 0.5f;
  float reprojectFrom = 0.75f;  // alpha from which vertices are pulled onto the posed field (1: never)
  bool operator==(const MorphProjection&) const = default;
};

// Optional cross-fade between the transitioned mesh and the implicit surface
// around markers B and C (for coarse meshes, where the switch shows): within
// widthFrames of the marker both are drawn, with complementary opacity
// (dithered), the implicit surface from 0 at B - width to 1 at B + width (and
// back to 0 from C - width to C + width). Display only: bake is unaffected.
struct MorphCrossFade {
  bool enabled = false;
  int widthFrames = 3;  // half-width of the window around each marker, >= 1
  bool operator==(const MorphCrossFade&) const = default;
};

// Measured on the demo (docs/morph.md, "Continuity"): bench morph-continuity.
inline constexpr float kDefaultInterpolationBound = 4.0f;

struct MorphSetup {
  std::string sourceActorId;  // empty: the project has no morph
  std::string targetActorId;
  MorphMarkers markers;
  MorphMethod method = MorphMethod::Interpolation;
  // SkeletonCorrespondence: how its two in-between stand-ins are combined
  // (Interpolation or SpaceTime; standin_morph/correspondence_morph.h).
  MorphMethod correspondenceBlend = MorphMethod::Interpolation;
  // SkeletonCorrespondence: the artist's chain pairings, at most one per source
  // chain (standin_morph/chain_pair.h); the automatic matching fills in the rest.
  std::vector<ChainPair> chainPairs;
  // Interpolation: each side's potential bounded at this many T before the
  // blend (standin_morph/morph_field.h: buildMorphProgram); <= 1: unbounded.
  float interpolationBound = kDefaultInterpolationBound;
  SpaceTimeParams spaceTime;
  FloatTrack easing;          // alpha over a transition's progress u in [0, 1]; default smoothstep
  FloatTrack blend;           // w over the morph's progress u in [0, 1]; default linear 0 -> 1
  float weightMapShift = 0.5f;  // fraction of a transition by which painted vertices start early
  FloatTrack noiseAmplitude{0.0f};  // solid-noise displacement (m) over the morph's progress
  float noiseFrequency = 8.0f;      // 1/m
  MorphProjection projection;
  MorphCrossFade crossFade;
  std::vector<ActorMorph> actors;

  MorphSetup();
  bool enabled() const { return !sourceActorId.empty() && !targetActorId.empty(); }
  ActorMorph* findActor(const std::string& id);
  const ActorMorph* findActor(const std::string& id) const;
  bool operator==(const MorphSetup& o) const;
};

// The default blend track: linear from 0 at u = 0 to 1 at u = 1.
FloatTrack linearBlendTrack();

}  // namespace animorph
