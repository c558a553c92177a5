#pragma once
// The continuity part of a bake's report (docs/morph.md, "Continuity"): every frame of a morph
// measured as it is baked, then summed up for animorph-cli bake's report: the frames that pop
// (standin_morph/morph_continuity.h finds them), the largest frame-to-frame volume change over the
// range and within B..C, and the continuity ratio over the range's part of A..D (the visible
// surface's largest jump against the characters' own motion, scene/morph_smoothness.h).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/export/project_frames.h"
#include "core/scene/morph_runtime.h"
#include "core/scene/morph_smoothness.h"
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
  MorphMarkers markers;                    // the morph's A..D
  // The continuity ratio over the range's part of A..D; none when that part is under two frames.
  std::optional<ContinuityRatio> ratio;
  bool ratioOverAtoD = false;  // that part is A..D whole
  // Up to five measured jumps, largest first: (the later frame of the pair, the jump in m).
  std::vector<std::pair<int, double>> largestJumps;
  int coreFrames = 0;  // frames that had a stand-in core inside the mesh (collapse, expansion)
};

// Collects a morph's frames as a bake makes them, in any order, from several threads at once (each
// frame writes its own slot), then sums them up.
class BakeContinuityMeter {
 public:
  // Frames first..first+count-1 of the morph rt (its markers and method go into the summary);
  // resolution: the BlobTree sides' polygonisation for the characters' own motion.
  BakeContinuityMeter(const MorphRuntime& rt, int first, int count, int resolution);
  // Frame first + k, baked with FrameBakeSettings::measure.
  void add(int k, const BakedFrame& frame);
  // After every frame was added; measures the characters' own motion over the ratio's frames.
  BakeContinuity summary() const;

 private:
  const MorphRuntime& rt_;
  int first_, resolution_;
  int ratioFirst_, ratioLast_;  // the range's part of A..D
  std::vector<FrameMeasure> measures_;
  std::vector<char> hadCore_;
  FrameJumpMeter jumps_;
};

}  // namespace animorph
