#include "cli/playblast.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "bake/frame_files.h"
#include "cli/cli_command.h"
#include "cli/progress_bar.h"
#include "vulkan/context.h"
#include "render/mesh_cache.h"
#include "present/offscreen_target.h"
#include "scene/mesh_character.h"
#include "render/scene_from_frame.h"
#include "render/scene_renderer.h"
#include "view/camera.h"

namespace animorph::cli {
namespace fs = std::filesystem;

int renderFrames(const std::vector<TriangleMesh>& meshes, int first, const ViewOptions& view, uint32_t width,
                 uint32_t height, const std::function<std::string(int, const gpu::RgbaImage&)>& frameOut) {
  gpu::ContextSettings cs;
  auto ctxR = gpu::Context::create(cs);
  if (!ctxR) return fail("bake", "--png: no usable Vulkan device: " + ctxR.error());
  gpu::Context& ctx = **ctxR;
  {
    auto target = gpu::OffscreenTarget::create(ctx, width, height);
    if (!target) return fail("bake", target.error());
    auto renderer = gpu::SceneRenderer::create(ctx, (*target)->renderPass());
    if (!renderer) return fail("bake", renderer.error());
    gpu::MeshCache cache(ctx);
    // One camera for the whole sequence, framing every frame.
    Bounds all;
    for (const auto& m : meshes)
      for (const auto& p : m.positions) all.add(p);
    OrbitCamera cam;
    cam.yawRad = glm::radians(35.0f);
    cam.pitchRad = glm::radians(20.0f);
    cam.frame(all, float(width) / float(height));
    ProgressBar bar("rendering", int(meshes.size()));
    for (size_t i = 0; i < meshes.size(); ++i) {
      SceneFrame frame;
      MeshDraw d;
      d.actorId = "morph";
      d.character = characterFromMesh(meshes[i], "baked");
      d.meshNode = 0;
      d.meshIndex = 0;
      d.joints = {glm::mat4(1.0f)};
      frame.meshes.push_back(d);
      gpu::Scene scene;
      ViewOptions v = view;
      v.showSkeleton = false;
      gpu::buildScene(frame, v, {}, cache, scene);
      gpu::ViewportRect rect{0, 0, width, height};
      Status recorded = Status::success();
      Status st = (*target)->render(
          [&](VkCommandBuffer cmd) { recorded = (*renderer)->record(cmd, (*target)->serial(), rect, cam, scene); },
          scene.options.background);
      if (!st) return fail("bake", st.error());
      if (!recorded) return fail("bake", recorded.error());
      if (std::string e = frameOut(first + int(i), (*target)->image()); !e.empty()) return fail("bake", e);
      cache.endFrame();
      bar.step();
    }
  }
  if (ctx.validationEnabled() && ctx.validationErrorCount() > 0) {
    std::fprintf(stderr, "animorph-cli bake: %u Vulkan validation error(s)\n", ctx.validationErrorCount());
    return 3;
  }
  return 0;
}

int renderPictures(const std::vector<TriangleMesh>& meshes, int first, const fs::path& dir, const std::string& name,
                   const ViewOptions& view, const PictureOptions& o) {
  if (o.png) {
    int code = renderFrames(meshes, first, view, 960, 540, [&](int f, const gpu::RgbaImage& img) -> std::string {
      Status w = gpu::writePng(frameFileName(dir.string(), name, f, "png"), img);
      return w ? std::string() : w.error();
    });
    if (code != 0) return code;
    std::printf("rendered %zu PNG frames into %s\n", meshes.size(), dir.string().c_str());
  }
  if (o.mp4.empty()) return 0;
  const std::string tmp = o.mp4 + ".part-" + std::to_string(long(getpid()));
  std::string filter;
  if (o.burnIn)  // DejaVu Sans Mono (fonts-dejavu-core, a dependency of ffmpeg's libass)
    filter = " -vf \"drawtext=fontfile=/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf:fontsize=" +
             std::to_string(std::max(12u, o.height / 24)) + ":fontcolor=white:box=1:boxcolor=black@0.5:x=10:y=10:"
             "text='frame %{eif\\:n+" + std::to_string(first) + "\\:d\\:4}'\"";
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", o.fps);
  const std::string cmd = "ffmpeg -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgba -s " +
                          std::to_string(o.width) + "x" + std::to_string(o.height) + " -r " + rate + " -i -" + filter +
                          " -c:v libx264 -preset veryfast -pix_fmt yuv420p -movflags +faststart -f mp4 '" + tmp + "'";
  FILE* pipe = popen(cmd.c_str(), "w");
  if (!pipe) return fail("bake", "--mp4: cannot start ffmpeg (Debian package ffmpeg)");
  const auto t0 = std::chrono::steady_clock::now();
  int code = renderFrames(meshes, first, view, o.width, o.height, [&](int, const gpu::RgbaImage& img) -> std::string {
    if (std::fwrite(img.pixels.data(), 1, img.pixels.size(), pipe) != img.pixels.size())
      return "--mp4: ffmpeg stopped taking frames (is ffmpeg installed?)";
    return {};
  });
  const int ff = pclose(pipe);
  std::error_code ec;
  if (code != 0 || ff != 0) {
    fs::remove(tmp, ec);
    return code != 0 ? code : fail("bake", "--mp4: ffmpeg failed (exit status " + std::to_string(ff) + ")");
  }
  fs::rename(tmp, o.mp4, ec);
  if (ec) return fail("bake", o.mp4 + ": cannot rename the finished file into place: " + ec.message());
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("wrote %s: %zu frames at %ux%u, %.1f frames/s rendered and encoded\n", o.mp4.c_str(), meshes.size(),
              o.width, o.height, sec > 0.0 ? double(meshes.size()) / sec : 0.0);
  return 0;
}

}  // namespace animorph::cli
