#include "core/export/bake_continuity.h"

namespace animorph {

BakeContinuityMeter::BakeContinuityMeter(const MorphRuntime& rt, int first, int count)
    : rt_(rt), first_(first), measures_(size_t(std::max(count, 0))) {}

void BakeContinuityMeter::add(int k, const TriangleMesh& mesh, size_t coreTriangles) {
  measures_[size_t(k)] = measureFrame(first_ + k, mesh, nullptr, coreTriangles);
}

BakeContinuity BakeContinuityMeter::summary() const {
  BakeContinuity c;
  c.method = morphMethodName(rt_.setup.method);
  c.frames = measures_;
  c.defects = continuityDefects(measures_);
  c.largestChangeFrame = first_;
  const MorphMarkers& mk = rt_.setup.markers;
  for (size_t k = 1; k < measures_.size(); ++k) {
    const double d = relativeVolumeChange(measures_[k - 1].volume, measures_[k].volume);
    if (d > c.largestChange) c.largestChange = d, c.largestChangeFrame = measures_[k].frame;
    if (measures_[k - 1].frame >= mk.b && measures_[k].frame <= mk.c && d >= c.largestChangeInside)
      c.largestChangeInside = d, c.largestChangeInsideFrame = measures_[k].frame;
  }
  return c;
}

}  // namespace animorph
