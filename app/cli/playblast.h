#pragma once
// Pictures of baked frames for animorph-cli bake (and its benchmark): PNG frames and the mp4
// playblast, rendered offscreen with one camera framing every frame (frame/playblast.h).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/export/frame_stage.h"
#include "core/project/project.h"
#include "core/poly/mesh.h"
#include "gpu/present/rgba_image.h"

namespace animorph::cli {

// What --png and --mp4 ask for, after the meshes are baked.
struct PictureOptions {
  bool png = false;
  std::string mp4;  // empty: none
  uint32_t width = 1280, height = 720;
  bool burnIn = false;  // the frame number and stage drawn into the mp4's corner
  std::vector<FrameStageSpan> stages;  // the stage labels burnt in (export/frame_stage.h)
  double fps = 24.0;
};

// Renders every mesh offscreen at width x height with one camera framing them all and hands each
// picture to frameOut (frame number, image; "" or the error). Returns the command's exit status
// (1 or 3 after printing the error).
int renderFrames(const std::vector<TriangleMesh>& meshes, int first, const ViewOptions& view, uint32_t width,
                 uint32_t height, const std::function<std::string(int, const gpu::RgbaImage&)>& frameOut);

// DIR/NAME_####.png (960x540) and/or the mp4 playblast: frames piped as raw RGBA to ffmpeg
// (H.264, yuv420p), written to a temporary name and renamed when ffmpeg succeeds. Exit status.
int renderPictures(const std::vector<TriangleMesh>& meshes, int first, const std::filesystem::path& dir,
                   const std::string& name, const ViewOptions& view, const PictureOptions& o);

}  // namespace animorph::cli
