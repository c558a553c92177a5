#pragma once
// Automatic stand-in fitting (docs/design.md §4), in world units with every
// node transform applied: one segment per bone (joint -> child joint), a short
// segment for leaf joints; joints that dominate no vertex (helper bones) are
// bridged -- a bone's segment runs to its nearest descendant joints that have
// vertices -- so the stand-in stays in one piece; a bone whose segment would
// be shorter than its radius (face and finger-tip bones, very short bones)
// gives its vertices to its parent's segment instead of adding a blob. Each
// radius is a robust percentile of the distances of the vertices the segment
// fits. Runs on the rest pose or a frame of a clip; the report
// (standin/fit_quality.h) says when the result is poor and which bones; a poor
// first fit is repaired where it can be (standin/repair_fit.h), before and after
// in the report.
#include <string>
#include <vector>

#include "core/rig/character.h"
#include "core/standin/fit_quality.h"
#include "core/standin/project_onto_standin.h"
#include "core/standin/repair_fit.h"
#include "core/standin/standin.h"
#include "core/util/result.h"

namespace animorph {

struct FitSettings {
  StandinKind kind = StandinKind::Convolution;
  // Percentile (0..1) of the dominated vertices' distances used as radius:
  // lower hugs thin parts, higher covers bulges. 0.6..0.75 fits most characters.
  float radiusPercentile = 0.65f;
  // Kernel sharpness as a multiple of 1 / (median radius): larger keeps bones
  // apart (tighter fit), smaller blends them into one blob.
  float sharpnessTimesRadius = 2.5f;
  // Bridge joints without vertices (helper bones): a bone's segment runs to its
  // nearest descendants with vertices. Off: to its child joints, as before.
  bool bridgeHelpers = true;
  // Fit small bones whose joint lies inside their parent's tube (face, finger
  // tips, very short bones) into the parent's segment instead of a blob of their own.
  bool mergeSmallBones = true;
  // Pose fitted: clip index (-1: rest pose) and time in that clip (seconds).
  int clip = -1;
  float clipTimeSec = 0.0f;
  // Measure the fit error by projecting every vertex (costs about one projection).
  bool measure = true;
  ProjectionSettings projection;
  FitQualitySettings quality;
  // Where the measured first fit is poor, repair it (standin/repair_fit.h): re-place segments on
  // the vertices bound to them, bridge detached pieces along the bone chain. Needs measure.
  FitRepairSettings repair;
};

struct FitResult {
  Standin standin;
  FitReport report;
};

// Fits a stand-in to c. Errors: no vertices, or a clip index out of range.
Result<FitResult> fitStandin(const Character& c, const FitSettings& settings = {});

// The fit error of an existing stand-in at the pose of settings (clip, time),
// with the quality checks of settings.quality.
FitReport measureStandinFit(const Character& c, const Standin& s, const FitSettings& settings);

}  // namespace animorph
