#include "core/scene/morph_smoothness.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/standin_morph/morph_continuity.h"
#include "core/scene/visible_surface.h"

namespace animorph {

namespace {

// One side alone at frame f: its skinned mesh, or its tree polygonised.
TriangleMesh sideAlone(const MorphRuntime& rt, bool target, int f, int resolution) {
  const double t = rt.timeline.frameToSec(f);
  MorphFrameSettings fs;
  fs.resolution = resolution;
  const MorphActorRuntime& a = target ? rt.target : rt.source;
  if (a.isTree()) {
    auto r = evaluateMorphImplicit(rt, t, target ? 1.0 : 0.0, fs);
    return r ? std::move(r->mesh) : TriangleMesh{};
  }
  return evaluateMorphTransition(rt, t, target, target ? 1.0 : 0.0, fs).mesh;
}

}  // namespace

OwnMotion charactersOwnMotion(const MorphRuntime& rt, int first, int last, int resolution) {
  OwnMotion m;
  for (bool target : {false, true}) {
    TriangleMesh prev = sideAlone(rt, target, first, resolution);
    for (int f = first + 1; f <= last; ++f) {
      TriangleMesh cur = sideAlone(rt, target, f, resolution);
      const double h = hausdorffDistance(prev, cur);
      if (std::isfinite(h) && h > m.hausdorff) {
        m.hausdorff = h;
        m.frame = f;
        m.actorId = (target ? rt.target : rt.source).actor.id;
      }
      prev = std::move(cur);
    }
  }
  return m;
}

void FrameJumpMeter::add(int frame, TriangleMesh visible) {
  if (frame < first_ || frame > last_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  waiting_[frame] = std::move(visible);
  for (auto it = waiting_.find(next_); it != waiting_.end(); it = waiting_.find(next_)) {
    if (next_ > first_) {
      const double h = hausdorffDistance(previous_, it->second);
      jumps_.push_back({next_, h});
      if (h > largest_ || (std::isinf(h) && !std::isinf(largest_))) {
        largest_ = h;
        largestFrame_ = next_;
      }
    }
    previous_ = std::move(it->second);
    waiting_.erase(it);
    ++next_;
  }
}

double ContinuityRatio::ratio() const {
  if (motion.hausdorff > 0.0) return jump / motion.hausdorff;
  return jump > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

std::string ContinuityRatio::describe() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.2fx: %.4f m at frame %d / own motion %.4f m (%s, frame %d), frames %d..%d",
                ratio(), jump, jumpFrame, motion.hausdorff, motion.actorId.c_str(), motion.frame, first, last);
  return buf;
}

Result<ContinuityRatio> measureContinuityRatio(const MorphRuntime& rt, const MorphFrameSettings& settings, int first,
                                               int last) {
  if (first > last) first = rt.setup.markers.a, last = rt.setup.markers.d;
  ContinuityRatio r;
  r.first = first;
  r.last = last;
  FrameJumpMeter meter(first, last);
  for (int f = first; f <= last; ++f) {
    if (settings.cancel && settings.cancel->load()) return Error{"cancelled"};
    auto fr = evaluateMorphFrame(rt, rt.timeline.frameToSec(f), settings);
    if (!fr) return Error{"frame " + std::to_string(f) + ": " + fr.error()};
    meter.add(f, visibleSurface(rt, *fr));
  }
  r.jump = meter.largestJump();
  r.jumpFrame = meter.largestJumpFrame();
  r.motion = charactersOwnMotion(rt, first, last, settings.resolution);
  return r;
}

}  // namespace animorph
