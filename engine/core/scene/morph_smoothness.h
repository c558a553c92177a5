#pragma once
// The continuity ratio of a morph (docs/morph.md, "Continuity"): the largest
// frame-to-frame jump of the visible surface over A..D (the symmetric Hausdorff
// distance between consecutive frames' visible surfaces, scene/visible_surface.h)
// divided by the characters' own largest per-frame motion over the same frames
// (each side's skinned mesh alone, no morph). A frame an animator calls a pop jumps
// far more than the characters move on their own; the bound held is 2.
#include <atomic>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/morph_runtime.h"
#include "core/poly/mesh.h"

namespace animorph {

inline constexpr double kMaxContinuityRatio = 2.0;

struct OwnMotion {
  double hausdorff = 0.0;  // m: the largest frame-to-frame distance of either side alone
  int frame = 0;           // the later frame of that pair
  std::string actorId;     // whose motion it is
};

// The characters' own motion over frames first..last: the source's and the
// target's skinned meshes (alpha 0), each frame against the one before; a
// BlobTree side is its tree polygonised at resolution.
OwnMotion charactersOwnMotion(const MorphRuntime& rt, int first, int last, int resolution);

// Collects frames first..last in any order, from any thread, and keeps the
// largest Hausdorff distance between consecutive ones (a frame is kept only
// until the next one has been measured against it).
class FrameJumpMeter {
 public:
  FrameJumpMeter(int first, int last) : first_(first), last_(last), next_(first) {}
  // Frame f's visible surface (ignored outside first..last).
  void add(int frame, TriangleMesh visible);
  double largestJump() const { return largest_; }  // m
  int largestJumpFrame() const { return largestFrame_; }
  bool complete() const { return next_ > last_; }  // every frame was added
  // Every measured pair: (the later frame, its jump in m), in frame order.
  const std::vector<std::pair<int, double>>& jumps() const { return jumps_; }

 private:
  int first_, last_, next_;
  std::mutex mutex_;
  std::map<int, TriangleMesh> waiting_;
  TriangleMesh previous_;
  double largest_ = 0.0;
  int largestFrame_ = 0;
  std::vector<std::pair<int, double>> jumps_;
};

struct ContinuityRatio {
  double jump = 0.0;  // m: the largest frame-to-frame jump of the visible surface
  int jumpFrame = 0;  // the later frame of that pair
  OwnMotion motion;
  int first = 0, last = 0;  // the frames measured
  // jump / motion.hausdorff; 0 when the characters do not move and nothing jumps,
  // infinite when they do not move and something jumps.
  double ratio() const;
  std::string describe() const;  // "1.62x: 0.060 m at frame 85 / own motion 0.037 m (creature, frame 30), frames 24..108"
};

// The ratio over frames first..last (A..D when first > last), every frame
// evaluated at settings' resolution (with the stand-in core when
// settings.standinCore) and its visible surface measured. cancel: stops early.
Result<ContinuityRatio> measureContinuityRatio(const MorphRuntime& rt, const MorphFrameSettings& settings,
                                               int first = 1, int last = 0);

}  // namespace animorph
