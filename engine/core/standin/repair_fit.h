#pragma once
// Automatic repair of a poor first stand-in fit (docs/morph.md, *Stand-in fitting*): a bone whose
// vertices lie far from its segments (a wide body on one spine bone, a bone whose joints sit outside
// the mesh) gets its segments re-placed on the vertices bound to it -- along their principal axis,
// one segment or several side by side across a wide section --, and a stand-in in more pieces than
// the mesh gets each detached piece bridged to the rest along the bone chain (a segment from the
// detached piece to its nearest related bone's segment, as thick as the mesh there). Each round is
// measured again (standin/fit_quality.h) and kept only when it is better; what was done is listed
// in the report, with the first fit's figures, so the user sees before and after.
#include <cstddef>
#include <vector>

#include "core/rig/character.h"
#include "core/standin/character_pose.h"
#include "core/standin/fit_quality.h"
#include "core/standin/project_onto_standin.h"
#include "core/standin/standin.h"

namespace animorph {

struct FitRepairSettings {
  // Off: the first fit is returned as it is (`fit --no-repair`, and the fitter's own tests).
  bool enabled = true;
  // Measure-and-repair rounds; each round costs about one fit measurement.
  int maxRounds = 3;
  // Repairs never grow the stand-in past this many segments: the GPU transitions re-project onto
  // at most 64 (morph/transition_frame.h); past it the editor falls back to the CPU.
  size_t maxSegments = 64;
  // A bone's segments are re-placed only when the new ones bring the mean distance of its vertices
  // to the surface down to this share of what it was (less: keeps the joint-to-joint segments).
  float replaceGain = 0.8f;
  // Up to this many segments side by side across a wide section of one bone.
  int maxSideBySide = 4;
};

// Repairs s, fitted to c at `pose` (the pose the fit was made on, root = identity), where
// `first` (its measurement with `quality`) says it is poor. vertexNode[i] is the node whose
// segments fit vertex i of the pose (-1: none). Returns the final report: first's figures in
// beforeRepair, each kept repair in repairs. When nothing helped, or the repaired fit is still
// poor, s and the report are the first fit's (the latter with a note of what was tried): a
// stand-in is either repaired into a fit that is not poor or left as it was. Never fails; with
// settings.enabled false or a fit that is not poor it returns `first` unchanged.
FitReport repairStandinFit(const Character& c, const CharacterPose& pose, const std::vector<int>& vertexNode,
                           Standin& s, const FitReport& first, const ProjectionSettings& projection,
                           const FitQualitySettings& quality, float radiusPercentile,
                           const FitRepairSettings& settings);

}  // namespace animorph
