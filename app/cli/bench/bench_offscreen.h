#pragma once
// What the offscreen editor-pipeline benchmarks (bench_scrub.cpp,
// bench_animorph_scrub.cpp) share: a Vulkan context with a 1280x720 offscreen
// target and the editor's scene renderer, one frame's render, and the
// figures they print (percentiles of frame times).
#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "gpu/present/offscreen_target.h"
#include "gpu/render/scene_renderer.h"
#include "gpu/vulkan/context.h"

namespace animorph::bench {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// The value at fraction p (0..1) of the sorted samples; 0 without samples.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size())))];
}

inline double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

// A device, an offscreen target of width x height and the scene renderer on it.
struct OffscreenBench {
  std::unique_ptr<gpu::Context> ctx;
  std::unique_ptr<gpu::OffscreenTarget> target;
  std::unique_ptr<gpu::SceneRenderer> renderer;
  uint32_t width = 1280, height = 720;

  // Empty on success, else why it failed ("no Vulkan device: ...").
  std::string create() {
    auto c = gpu::Context::create(gpu::ContextSettings{});
    if (!c) return "no Vulkan device: " + c.error();
    ctx = std::move(*c);
    auto t = gpu::OffscreenTarget::create(*ctx, width, height);
    if (!t) return t.error();
    target = std::move(*t);
    auto r = gpu::SceneRenderer::create(*ctx, target->renderPass());
    if (!r) return r.error();
    renderer = std::move(*r);
    return {};
  }

  // Renders scene seen by camera into the target (no read-back). Empty on success.
  std::string render(const OrbitCamera& camera, const gpu::Scene& scene) {
    std::string error;
    Status st = target->render(
        [&](VkCommandBuffer cmd) {
          Status r = renderer->record(cmd, target->serial(), {0, 0, width, height}, camera, scene);
          if (!r) error = r.error();
        },
        {0.1f, 0.1f, 0.1f, 1.0f}, /*readBack=*/false);
    if (!st) error = st.error();
    return error;
  }
};

}  // namespace animorph::bench
