#include "app/cli/playblast.h"

#include <cstdio>

#include "core/export/frame_files.h"
#include "app/cli/cli_command.h"
#include "app/cli/progress_bar.h"
#include "gpu/frame/mesh_sequence_renderer.h"
#include "gpu/frame/playblast.h"

namespace animorph::cli {
namespace fs = std::filesystem;

int renderFrames(const std::vector<TriangleMesh>& meshes, int first, const ViewOptions& view, uint32_t width,
                 uint32_t height, const std::function<std::string(int, const gpu::RgbaImage&)>& frameOut) {
  auto renderer = gpu::MeshSequenceRenderer::create(width, height, view);
  if (!renderer) return fail("bake", "--png: " + renderer.error());
  Bounds all;  // one camera for the whole sequence, framing every frame
  for (const auto& m : meshes)
    for (const auto& p : m.positions) all.add(p);
  (*renderer)->frameBounds(all);
  ProgressBar bar("rendering", int(meshes.size()));
  for (size_t i = 0; i < meshes.size(); ++i) {
    auto image = (*renderer)->render(meshes[i]);
    if (!image) return fail("bake", image.error());
    if (std::string e = frameOut(first + int(i), **image); !e.empty()) return fail("bake", e);
    bar.step();
  }
  if (uint32_t n = (*renderer)->validationErrors(); n > 0) {
    std::fprintf(stderr, "animorph-cli bake: %u Vulkan validation error(s)\n", n);
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
  Mp4Options mo;
  mo.path = o.mp4;
  mo.width = o.width;
  mo.height = o.height;
  mo.fps = o.fps;
  mo.burnIn = o.burnIn;
  mo.firstFrame = first;
  mo.stages = o.stages;
  auto r = gpu::playblastMeshes(meshes, view, mo, std::nullopt, nullptr);
  if (!r) return fail("bake", "--mp4: " + r.error());
  std::printf("wrote %s: %d frames at %dx%d, %.1f frames/s rendered and encoded\n", o.mp4.c_str(), r->frames,
              r->width, r->height, r->pictureSeconds > 0.0 ? double(r->frames) / r->pictureSeconds : 0.0);
  return 0;
}

}  // namespace animorph::cli
