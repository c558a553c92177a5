#include "core/export/bake_continuity.h"

#include <algorithm>

namespace animorph {

BakeContinuityMeter::BakeContinuityMeter(const MorphRuntime& rt, int first, int count, int resolution)
    : rt_(rt),
      first_(first),
      resolution_(resolution),
      ratioFirst_(std::max(first, rt.setup.markers.a)),
      ratioLast_(std::min(first + count - 1, rt.setup.markers.d)),
      measures_(size_t(std::max(count, 0))),
      hadCore_(size_t(std::max(count, 0)), 0),
      jumps_(ratioFirst_, ratioLast_) {}

void BakeContinuityMeter::add(int k, const BakedFrame& frame) {
  measures_[size_t(k)] = frame.measure;
  hadCore_[size_t(k)] = frame.coreTriangles > 0;
  const int f = first_ + k;
  if (f >= ratioFirst_ && f <= ratioLast_) jumps_.add(f, frame.visibleMesh());
}

BakeContinuity BakeContinuityMeter::summary() const {
  BakeContinuity c;
  c.method = morphMethodName(rt_.setup.method);
  c.frames = measures_;
  c.defects = continuityDefects(measures_);
  c.largestChangeFrame = first_;
  const MorphMarkers& mk = rt_.setup.markers;
  c.markers = mk;
  for (size_t k = 1; k < measures_.size(); ++k) {
    const double d = relativeVolumeChange(measures_[k - 1].volume, measures_[k].volume);
    if (d > c.largestChange) c.largestChange = d, c.largestChangeFrame = measures_[k].frame;
    if (measures_[k - 1].frame >= mk.b && measures_[k].frame <= mk.c && d >= c.largestChangeInside)
      c.largestChangeInside = d, c.largestChangeInsideFrame = measures_[k].frame;
  }
  c.coreFrames = int(std::count(hadCore_.begin(), hadCore_.end(), 1));
  if (ratioLast_ > ratioFirst_) {
    ContinuityRatio r;
    r.first = ratioFirst_;
    r.last = ratioLast_;
    r.jump = jumps_.largestJump();
    r.jumpFrame = jumps_.largestJumpFrame();
    r.motion = charactersOwnMotion(rt_, ratioFirst_, ratioLast_, resolution_);
    c.ratio = r;
    c.ratioOverAtoD = ratioFirst_ == mk.a && ratioLast_ == mk.d;
    c.largestJumps = jumps_.jumps();
    std::sort(c.largestJumps.begin(), c.largestJumps.end(),
                     [](const auto& x, const auto& y) { return x.second > y.second; });
    if (c.largestJumps.size() > 5) c.largestJumps.resize(5);
  }
  return c;
}

}  // namespace animorph
