// Benchmark of the playblast (bake --mp4, File > Export > Playblast...): frames of the demo morph
// rendered offscreen at 1280x720 and encoded by ffmpeg with the burn-in, with rendering alone (the
// pictures dropped) as the baseline in the same run.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/export/frame_stage.h"
#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_demo_project.h"
#include "app/cli/bench/bench_scratch_dir.h"
#include "app/cli/playblast.h"
#include "core/project/project_io.h"
#include "core/scene/morph_runtime.h"

namespace {

using namespace animorph;
using animorph::bench::Row;
namespace fs = std::filesystem;

std::vector<Row> benchPlayblast(const bench::Options& opt) {
  const bench::DemoMorph dm = bench::loadDemoMorph();
  if (!dm.error.empty()) return {{"skipped", 0, "", "", dm.error}};
  const Project* project = &dm.project;
  const auto* rt = &dm.runtime;
  // Frames around B (collapse and morph), baked once at 32^3: the figure is the pictures'.
  const int first = 36, count = opt.quick ? 12 : 48;
  std::vector<TriangleMesh> meshes;
  for (int f = first; f < first + count; ++f) {
    MorphFrameSettings s;
    s.resolution = 32;
    auto fr = evaluateMorphFrame(**rt, project->timeline.frameToSec(f), s);
    if (!fr) return {{"skipped", 0, "", "", "frame " + std::to_string(f) + ": " + fr.error()}};
    meshes.push_back(std::move(fr->mesh));
  }
  const bench::ScratchDir scratch("animorph-bench-playblast");
  if (!scratch.ok()) return {{"skipped", 0, "", "", "cannot create a temporary directory"}};
  const std::string tmpl = scratch.path().string();
  cli::PictureOptions o;
  o.mp4 = (fs::path(tmpl) / "demo.mp4").string();
  o.fps = project->timeline.fps;
  o.burnIn = true;  // as the editor's playblast does by default: the frame number and stage
  o.stages = frameStageSpans(*project, first, first + count - 1);
  auto t0 = std::chrono::steady_clock::now();
  int code = cli::renderFrames(meshes, first, project->view, o.width, o.height,
                               [](int, const gpu::RgbaImage&) { return std::string(); });
  const double renderSec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  if (code == 0) code = cli::renderPictures(meshes, first, tmpl, "demo", project->view, o);
  const double totalSec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (code != 0) return {{"skipped", 0, "", "", "rendering or ffmpeg failed (exit " + std::to_string(code) + ")"}};
  char note[160];
  std::snprintf(note, sizeof note, "%d frames; baseline: rendering alone %.1f frames/s (the rest is ffmpeg's H.264)",
                count, count / renderSec);
  return {{"playblast 1280x720 (render + encode + burn-in)", count / totalSec, "frames/s", ">= 10 frames/s", note}};
}

}  // namespace

ANIMORPH_BENCH("playblast", "the demo morph's playblast at 1280x720: render offscreen + ffmpeg (baseline: render only)",
               benchPlayblast);
