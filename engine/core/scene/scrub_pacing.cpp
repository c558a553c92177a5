#include "core/scene/scrub_pacing.h"

#include <algorithm>

namespace animorph {

double ScrubPacer::intervalFor(double fps) {
  return fps > 0.0 ? std::clamp(1.0 / fps, 1.0 / 60.0, 1.0 / 24.0) : 1.0 / 24.0;
}

double ScrubPacer::waitSec(double nowSec, uint64_t events, uint64_t meshes) const {
  if (meshes != meshes_) return 0.0;  // a new mesh to show
  const double due = frameSec_ + (events != events_ ? intervalSec_ : kMaxWaitSec);
  return std::max(0.0, due - nowSec);
}

}  // namespace animorph
