#pragma once
// The continuity part of a bake's report (docs/morph.md, "Continuity"): every frame of a morph
// measured as it is baked (standin_morph/morph_continuity.h does the measuring and finds the
// defects), then summed up for animorph-cli bake's report: the frames that pop, and the largest
// frame-to-frame volume change over the range and within B..C.
#include <string>
#include <vector>

#include "core/scene/morph_runtime.h"
#include "core/standin_morph/morph_continuity.h"

namespace animorph {

struct BakeContinuity {
  std::string method;                      // the morph's method (morphMethodName)
  std::vector<FrameMeasure> frames;        // one per frame of the range, in order
  std::vector<ContinuityDefect> defects;   // continuityDefects(frames)
  double largestChange = 0.0;              // largest relativeVolumeChange between consecutive frames
  int largestChangeFrame = 0;              // the later frame of that pair (the first frame when none)
  double largestChangeInside = 0.0;        // the same over pairs of frames within B..C
  int largestChangeInsideFrame = -1;       // -1: the range holds no pair of frames within B..C
};

// Collects a morph's frames as a bake makes them, in any order, from several threads at once (each
// frame writes its own slot), then sums them up.
class BakeContinuityMeter {
 public:
  // Frames first..first+count-1 of the morph rt (its markers and method go into the summary).
  BakeContinuityMeter(const MorphRuntime& rt, int first, int count);
  // Frame first + k's mesh; coreTriangles as MorphFrame::coreTriangles.
  void add(int k, const TriangleMesh& mesh, size_t coreTriangles);
  // After every frame was added.
  BakeContinuity summary() const;

 private:
  const MorphRuntime& rt_;
  int first_;
  std::vector<FrameMeasure> measures_;
};

}  // namespace animorph
