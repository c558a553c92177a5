// Benchmark of the editor's implicit preview while scrubbing: the demo morph's
// B..C stage (creature -> gear) scrubbed frame by frame, forward then back,
// through the editor's own pipeline (scene evaluation, the morph's stage, the
// ImplicitPreview at the interactive resolution, the renderer into an
// offscreen 1280x720 target; no window), once with the CPU worker and once
// with the GPU polygoniser. Prints frame time p50/p95, fps, the preview's
// latency (a time's mesh on screen after the frame that asked for it), and how
// long refining takes once scrubbing stops.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_offscreen.h"
#include "core/project/project_io.h"
#include "core/scene/morph_preview_source.h"
#include "core/scene/morph_scene.h"
#include "core/scene/scene_frame.h"
#include "gpu/polygonizer/implicit_preview.h"
#include "gpu/render/mesh_cache.h"
#include "gpu/frame/scene_from_frame.h"

namespace {

using namespace animorph;
using animorph::bench::Clock;
using animorph::bench::msSince;
using animorph::bench::percentile;
using animorph::bench::Row;

// What every mode of the scrub shares: the demo, its morph, the offscreen renderer and the frames.
struct ScrubSetup {
  const Project& project;
  const std::string& baseDir;
  AssetCache& assets;
  const std::shared_ptr<const MorphRuntime>& rt;
  bench::OffscreenBench& off;
  const std::vector<int>& frames;  // B..C..B
  int interactive, refined;        // the preview's resolutions
  const OrbitCamera& camera;
};

// One mode: 0 the CPU worker, 1 the GPU as the editor runs it (frame pacing), 2 the GPU
// polygonising every frame's shape. Appends its rows (a failed row on a render error).
void scrubOneMode(const ScrubSetup& setup, int mode, std::vector<Row>& rows) {
  const Project& project = setup.project;
  const std::string& baseDir = setup.baseDir;
  AssetCache& assets = setup.assets;
  const std::shared_ptr<const MorphRuntime>& rt = setup.rt;
  bench::OffscreenBench& off = setup.off;
  const std::vector<int>& frames = setup.frames;
  const int interactive = setup.interactive, refined = setup.refined;
  const OrbitCamera& camera = setup.camera;
  const Timeline& tl = project.timeline;
  const bool gpuPath = mode > 0;
  const std::string tag = std::string(gpuPath ? "GPU" : "CPU") + " preview " + std::to_string(interactive) + "^3" +
                          (mode == 2 ? " every frame" : "");
  gpu::ImplicitPreview preview(*off.ctx);
  gpu::MeshCache meshes(*off.ctx);
  gpu::Scene scene;
  gpu::ImplicitPreviewSettings ps;
  ps.interactiveResolution = interactive;
  ps.refinedResolution = refined;
  ps.gpu = gpuPath;
  ps.paceGpu = mode != 2;
  ps.threads = interactivePreviewThreads();  // as the editor
  std::vector<double> frameMs, latencyMs;
  std::map<double, Clock::time_point> askedAt;  // time -> when a frame last started asking for it
  double lastAnswered = -1.0, lastAsked = -1.0;
  std::string error;
  auto oneFrame = [&](double timeSec) {
    SceneFrame frame = evaluateScene(project, baseDir, assets, timeSec);
    applyMorph(frame, *rt, timeSec, MorphFrameSettings{}, /*implicitStage=*/false);
    if (timeSec != lastAsked) askedAt[timeSec] = Clock::now();  // a new time (re)starts its clock
    lastAsked = timeSec;
    preview.update(morphPreviewSource(rt, timeSec), timeSec, ps);
    gpu::buildScene(frame, project.view, {}, meshes, scene);
    preview.draw(scene, glm::mat4(1.0f), {0.62f, 0.62f, 0.62f, 1.0f}, false);
    if (std::string e = off.render(camera, scene); !e.empty()) error = e;
    meshes.endFrame();
    preview.endFrame();
    // Latency: from the frame that first asked for a time to the end of the frame that drew
    // its mesh (CPU: the worker's result, uploaded; GPU: the shape recorded, drawn in the same
    // frame). Times never drawn (skipped while scrubbing) have no latency: "meshes shown".
    if (double shown = preview.status().timeSec; shown != lastAnswered && askedAt.count(shown)) {
      lastAnswered = shown;
      latencyMs.push_back(msSince(askedAt[shown]));
    }
  };
  // Warm-up: pipelines (the B marker's field is one stand-in, the frames after it a morph:
  // two pipeline variants), first uploads, buffers grown for both resolutions (each shape
  // settles at the refined one).
  for (int w = 1; w >= 0; --w) {
    oneFrame(tl.frameToSec(frames[size_t(w)]));
    while (preview.busy()) {
      preview.waitIdle(60.0);
      oneFrame(tl.frameToSec(frames[size_t(w)]));
    }
  }
  askedAt.clear();
  latencyMs.clear();  // the warm-up's frames (pipeline compilation) are not scrubbing
  for (int f : frames) {
    const auto t0 = Clock::now();
    oneFrame(tl.frameToSec(f));
    frameMs.push_back(msSince(t0));
  }
  // Scrubbing stops: frames keep coming until the refined mesh is on screen.
  const auto stop = Clock::now();
  const double stopTime = tl.frameToSec(frames.back());
  int settleFrames = 0;
  while (preview.busy() && msSince(stop) < 60000.0) {
    oneFrame(stopTime);
    ++settleFrames;
  }
  const double refineMs = msSince(stop);
  const gpu::ImplicitPreviewStatus st = preview.status();
  if (!error.empty()) {
    rows.push_back({tag + " failed", 0, "", "", error});
    return;
  }
  std::string how = st.gpu ? "GPU" : "CPU";
  if (!st.gpuFallback.empty()) how += " (fell back: " + st.gpuFallback + ")";
  const double mean = bench::mean(frameMs);
  rows.push_back({tag + " frame time p50", percentile(frameMs, 0.5), "ms", "", how});
  rows.push_back({tag + " frame time p95", percentile(frameMs, 0.95), "ms", "", ""});
  rows.push_back({tag + " fps", 1000.0 / mean, "fps", ">= 30", "mean over the scrub"});
  rows.push_back({tag + " preview latency p50", percentile(latencyMs, 0.5), "ms", "",
                  std::to_string(latencyMs.size()) + " meshes shown while scrubbing"});
  rows.push_back({tag + " preview latency p95", percentile(latencyMs, 0.95), "ms", "", ""});
  char note[128];
  std::snprintf(note, sizeof note, "%d frames; %d^3, %zu tris", settleFrames, st.resolution, st.triangles);
  rows.push_back({tag + " refine to " + std::to_string(refined) + "^3 after scrubbing", refineMs, "ms", "", note});
}

std::vector<Row> runScrub(const animorph::bench::Options& opt) {
  std::vector<Row> rows;
  namespace fs = std::filesystem;
  const char* demoEnv = std::getenv("ANIMORPH_DEMO");
  const fs::path demo = demoEnv ? fs::path(demoEnv) : fs::path(ANIMORPH_SOURCE_DIR) / "resources/demo/demo.animorph";
  auto project = loadProject(demo.string());
  if (!project) {
    rows.push_back({"skipped", 0, "", "", project.error()});
    return rows;
  }
  const std::string baseDir = demo.parent_path().string();
  AssetCache assets;
  auto rt = prepareMorph(*project, baseDir, assets);
  if (!rt) {
    rows.push_back({"skipped", 0, "", "", rt.error()});
    return rows;
  }
  bench::OffscreenBench off;
  if (std::string why = off.create(); !why.empty()) {
    rows.push_back({"skipped", 0, "", "", why});
    return rows;
  }
  const MorphMarkers& mk = project->morph.markers;
  std::vector<int> frames;
  const int last = opt.quick ? std::min(mk.c, mk.b + 6) : mk.c;
  for (int f = mk.b; f <= last; ++f) frames.push_back(f);
  for (int f = last - 1; f >= mk.b; --f) frames.push_back(f);
  const int interactive = opt.quick ? 48 : 96, refined = opt.quick ? 64 : 128;
  rows.push_back({"device", 0, "", "", off.ctx->deviceName() + "; " + std::to_string(frames.size()) +
                                           " frames B..C..B of the demo morph, 1280x720 offscreen"});
  OrbitCamera camera;
  Bounds view;
  view.add(glm::vec3(-1.2f, 0.0f, -1.2f));
  view.add(glm::vec3(1.2f, 2.0f, 1.2f));
  camera.frame(view, float(off.width) / float(off.height));

  // CPU worker; GPU as the editor runs it (frame pacing); GPU polygonising every frame's shape.
  const ScrubSetup setup{*project, baseDir, assets, *rt, off, frames, interactive, refined, camera};
  for (int mode : {0, 1, 2}) scrubOneMode(setup, mode, rows);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("scrub", "editor preview pipeline scrubbing the demo morph B..C, CPU worker vs GPU (offscreen)",
               runScrub);
