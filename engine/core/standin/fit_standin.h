#pragma once
// Automatic stand-in fitting (docs/design.md §4): one segment per bone (joint ->
// child joint), a short segment for leaf joints, bones that dominate no vertex
// omitted; each radius is a robust percentile of the distances of the
// vertices the bone dominates. Runs on the rest pose or a frame of a clip.
#include <string>
#include <vector>

#include "rig/character.h"
#include "standin/project_onto_standin.h"
#include "standin/standin.h"
#include "util/result.h"

namespace animorph {

struct FitSettings {
  StandinKind kind = StandinKind::Convolution;
  // Percentile (0..1) of the dominated vertices' distances used as radius:
  // lower hugs thin parts, higher covers bulges. 0.6..0.75 fits most characters.
  float radiusPercentile = 0.65f;
  // Kernel sharpness as a multiple of 1 / (median radius): larger keeps bones
  // apart (tighter fit), smaller blends them into one blob.
  float sharpnessTimesRadius = 2.5f;
  // Pose fitted: clip index (-1: rest pose) and time in that clip (seconds).
  int clip = -1;
  float clipTimeSec = 0.0f;
  // Measure the fit error by projecting every vertex (costs about one projection).
  bool measure = true;
  ProjectionSettings projection;
};

struct FitReport {
  size_t segments = 0;
  size_t bonesOmitted = 0;      // rig nodes that dominate no vertex
  double diagonal = 0.0;        // bounding-box diagonal of the fitted pose (m)
  double meanError = 0.0;       // mean vertex distance to the stand-in surface / diagonal
  double maxError = 0.0;        // max distance / diagonal
  ProjectionStats projection;   // of the measurement
  double milliseconds = 0.0;    // fitting and measuring
  std::vector<std::string> notes;
};

struct FitResult {
  Standin standin;
  FitReport report;
};

// Fits a stand-in to c. Errors: no vertices, or a clip index out of range.
Result<FitResult> fitStandin(const Character& c, const FitSettings& settings = {});

// The fit error of an existing stand-in at the pose of settings (clip, time).
FitReport measureStandinFit(const Character& c, const Standin& s, const FitSettings& settings);

}  // namespace animorph
