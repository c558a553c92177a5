// Benchmark of the editor scrubbing the animorphosis demo (dinosaur -> dragon,
// resources/demo/animorphosis.animorph) through its interval, forward then
// back, through the editor's own pipeline: scene evaluation, the animorphosis'
// C(t) preview source (scene/animorphosis_scene.h: C compiled directly), the BlobTree previews at the
// interactive resolution (96^3; the CPU worker, then the GPU polygoniser), the
// renderer into an offscreen 1280x720 target (no window). A simulated cursor moves the playhead
// a timeline frame every 1/48 s. The CPU worker is measured twice: with the loop drawing a frame
// at once after each (as the editor did) and with the editor's scrub pacing (scene/scrub_pacing.h:
// a frame per new mesh, input at most once a paced interval, the worker on every hardware thread).
// The frame loop never waits for a polygoniser, so two figures matter: frames per second of the
// loop, and new C(t) meshes shown per second while scrubbing (what the artist sees move); plus how
// long input waits for its frame, and how long the preview takes to settle at 128^3 once
// scrubbing stops.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <filesystem>

#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_offscreen.h"
#include "core/blobtree/compile.h"
#include "core/project/project_io.h"
#include "gpu/polygonizer/blob_preview_set.h"
#include "core/poly/preview_polygonizer.h"
#include "gpu/render/mesh_cache.h"
#include "gpu/frame/scene_from_frame.h"
#include "core/scene/animorphosis_scene.h"
#include "core/scene/scene_frame.h"
#include "core/scene/scrub_pacing.h"

namespace {

using namespace animorph;
using namespace animorph::bench;

std::vector<Row> runAnimorphScrub(const Options& opt) {
  std::vector<Row> rows;
  namespace fs = std::filesystem;
  const fs::path demo = fs::path(ANIMORPH_SOURCE_DIR) / "resources/demo/animorphosis.animorph";
  auto project = loadProject(demo.string());
  if (!project) return {{"skipped", 0, "", "", project.error()}};
  if (!project->animorphosis.enabled()) return {{"skipped", 0, "", "", "the demo has no animorphosis"}};
  const std::string baseDir = demo.parent_path().string();
  OffscreenBench off;
  if (std::string why = off.create(); !why.empty()) return {{"skipped", 0, "", "", why}};

  // The middle of the interval, a frame at a time (24 fps), forward then back.
  const Timeline& tl = project->timeline;
  const int f0 = int(tl.secToFrame(project->animorphosis.startSec) + 0.5),
            f1 = int(tl.secToFrame(project->animorphosis.endSec) + 0.5);
  const int span = opt.quick ? 4 : 24, mid = (f0 + f1) / 2;
  std::vector<int> frames;
  const int passes = opt.quick ? 1 : 2;  // forward then back, twice: ~4 s of cursor moves
  for (int pass = 0; pass < passes; ++pass) {
    for (int f = mid - span + (pass > 0); f <= mid + span; ++f) frames.push_back(f);
    for (int f = mid + span - 1; f >= mid - span; --f) frames.push_back(f);
  }
  const int interactive = opt.quick ? 48 : 96, refined = opt.quick ? 64 : 128;
  AssetCache assets;
  AnimorphosisCache cache;
  std::string actorId;
  Bounds view;
  {
    SceneFrame frame = evaluateScene(*project, baseDir, assets, tl.frameToSec(mid));
    applyAnimorphosis(frame, *project, cache, &*project, 0);
    if (frame.blobs.empty() || !frame.blobs.front().source) return {{"skipped", 0, "", "", "no C(t) draw at the middle"}};
    actorId = frame.blobs.front().actorId;
    view = compileFieldProgram(*frame.blobs.front().ownTree(), 0.0).bounds();
  }
  rows.push_back({"device", 0, "", "",
                  off.ctx->deviceName() + "; " + std::to_string(frames.size()) + " frames " +
                      std::to_string(frames.front()) + ".." + std::to_string(frames.front() + 2 * span) + ".." +
                      std::to_string(frames.back()) + (passes > 1 ? " (twice)" : "") +
                      " of the animorphosis demo, 1280x720 offscreen; the cursor moves a frame every 1/48 s"});
  OrbitCamera camera;
  camera.frame(view, float(off.width) / float(off.height));

  constexpr double kMovesPerSec = 48.0;  // the cursor: about the speed the unpaced loop scrubbed at here
  struct Mode {
    bool gpu, paced;
    const char* policy;
  };
  for (const Mode mode : {Mode{false, false, ", redraw at once"}, Mode{false, true, ", paced"}, Mode{true, false, ""}}) {
    const bool gpuPath = mode.gpu;
    if (gpuPath && !opt.gpu && off.ctx->deviceType() == VK_PHYSICAL_DEVICE_TYPE_CPU) {
      rows.push_back({"GPU preview: skipped", 0, "", "", "a CPU Vulkan device (run with --gpu to measure it anyway)"});
      continue;
    }
    const std::string tag = std::string(gpuPath ? "GPU" : "CPU") + " preview of C(t) at " + std::to_string(interactive) +
                            "^3" + mode.policy;
    gpu::BlobPreviewSet previews(*off.ctx);
    gpu::MeshCache meshes(*off.ctx);
    gpu::BlobPreviewSettings ps{interactive, refined, interactivePreviewThreads(), gpuPath, false};
    ScrubPacer pacer(ScrubPacer::intervalFor(tl.fps));
    bool paced = false;  // the previous frame paced the loop (the editor's viewport_frame: its threads)
    int scrubThreads = 0;  // the most polygoniser threads a scrubbing frame asked for
    std::vector<double> frameMs, polyMs, inputWaitMs;
    double stageMs[4] = {0, 0, 0, 0};  // evaluate the scene, C(t) into it, previews.update, draw
    std::string error;
    size_t meshesShown = 0;
    gpu::ImplicitPreviewStatus last;
    auto oneFrame = [&](double timeSec) {
      auto t = Clock::now();
      auto lap = [&](int stage) {
        stageMs[stage] += msSince(t);
        t = Clock::now();
      };
      SceneFrame frame = evaluateScene(*project, baseDir, assets, timeSec);
      lap(0);
      applyAnimorphosis(frame, *project, cache, &*project, 0);
      lap(1);
      ps.threads = paced ? pacedPreviewThreads() : interactivePreviewThreads();
      previews.update(*project, frame, ps);
      lap(2);
      gpu::Scene scene;
      gpu::buildScene(frame, project->view, {}, meshes, scene, &previews);
      if (std::string e = off.render(camera, scene); !e.empty()) error = e;
      lap(3);
      meshes.endFrame();
      previews.endFrame();
      // A new mesh on screen: its polygonisation time or triangle count differs from the last one's.
      const gpu::ImplicitPreviewStatus st = previews.status(actorId);
      if (st.hasMesh && (st.milliseconds != last.milliseconds || st.triangles != last.triangles)) {
        ++meshesShown;
        polyMs.push_back(st.milliseconds);
      }
      last = st;
      if (!st.error.empty()) error = st.error;
    };
    // Warm-up: the first shape (GPU pipelines compile, buffers grow), settled.
    const auto warm = Clock::now();
    oneFrame(tl.frameToSec(frames.front()));
    while (previews.busy() && msSince(warm) < 120000.0) {
      previews.waitIdle(1.0);
      oneFrame(tl.frameToSec(frames.front()));
    }
    meshesShown = 0;
    polyMs.clear();
    for (double& m : stageMs) m = 0.0;
    const gpu::PreviewFieldCounters fieldsBefore = previews.fieldCounters(actorId);
    const auto scrubStart = Clock::now();
    const std::clock_t cpuStart = std::clock();  // the process's processor time: how busy the cores were
    auto inputNow = [&](double& nowSec) {  // cursor moves so far
      nowSec = msSince(scrubStart) / 1000.0;
      return size_t(nowSec * kMovesPerSec);
    };
    size_t shown = 0;  // moves a frame has shown (the first is the warm-up's)
    for (;;) {
      double nowSec = 0.0;
      const size_t moves = inputNow(nowSec);
      if (moves >= frames.size()) break;
      // Every move since the last frame waited until this one (a skipped move too: a later one shows it).
      for (; shown <= moves; ++shown) inputWaitMs.push_back(1000.0 * (nowSec - double(shown) / kMovesPerSec));
      pacer.frameStarted(nowSec, moves, PreviewPolygonizer::publishedTotal());
      const auto t0 = Clock::now();
      oneFrame(tl.frameToSec(frames[moves]));
      frameMs.push_back(msSince(t0));
      scrubThreads = std::max(scrubThreads, ps.threads);
      // The editor's loop (app/editor/main.cpp): paced while the worker computes, else the next frame at once.
      paced = mode.paced && ScrubPacer::applies(true, previews.busy(), previews.needsFrames());
      for (double waitSec = 1.0; paced && waitSec > 0.0;) {
        const uint64_t seen = PreviewPolygonizer::publishedTotal();
        const size_t now = inputNow(nowSec);
        waitSec = pacer.waitSec(nowSec, now, seen);
        // Woken by a published mesh, or by the next cursor move (a window event in the editor).
        if (waitSec > 0.0)
          PreviewPolygonizer::waitForPublish(seen, std::min(waitSec, double(now + 1) / kMovesPerSec - nowSec));
      }
    }
    const double scrubMs = msSince(scrubStart);
    const double cores = 1000.0 * double(std::clock() - cpuStart) / CLOCKS_PER_SEC / scrubMs;
    char stages[160];
    const double n = double(frameMs.size());
    std::snprintf(stages, sizeof stages, "evaluate the scene %.1f, C(t) into it %.1f, previews %.1f, draw %.1f ms",
                  stageMs[0] / n, stageMs[1] / n, stageMs[2] / n, stageMs[3] / n);
    gpu::PreviewFieldCounters fields = previews.fieldCounters(actorId);
    fields.onCompileThread -= fieldsBefore.onCompileThread;
    fields.onCallerThread -= fieldsBefore.onCallerThread;
    fields.compileThreadMs -= fieldsBefore.compileThreadMs;
    fields.callerThreadMs -= fieldsBefore.callerThreadMs;
    fields.superseded -= fieldsBefore.superseded;
    const size_t shownWhileScrubbing = meshesShown;
    const std::vector<double> polyWhileScrubbing = polyMs;
    // Scrubbing stops: frames keep coming until the refined mesh is on screen.
    const auto stop = Clock::now();
    int settleFrames = 0;
    while (previews.busy() && msSince(stop) < 60000.0) {
      const uint64_t seen = PreviewPolygonizer::publishedTotal();
      oneFrame(tl.frameToSec(frames.back()));
      ++settleFrames;
      // Idle, the editor waits for the worker's next mesh (or its poll) instead of redrawing.
      if (mode.paced) PreviewPolygonizer::waitForPublish(seen, ScrubPacer::kMaxWaitSec);
    }
    const double refineMs = msSince(stop);
    const gpu::ImplicitPreviewStatus st = previews.status(actorId);
    if (!error.empty()) {
      rows.push_back({tag + ": failed", 0, "", "", error});
      continue;
    }
    std::string how = st.gpu ? "GPU" : "CPU, up to " + std::to_string(scrubThreads) + " threads";
    if (!st.gpuFallback.empty()) how += " (fell back: " + st.gpuFallback + ")";
    rows.push_back({tag + ", frame loop", 1000.0 * double(frameMs.size()) / scrubMs, "fps", "",
                    std::to_string(frameMs.size()) + " frames drawn; frame time p50 " +
                        std::to_string(int(percentile(frameMs, 0.5) + 0.5)) + " ms, p95 " +
                        std::to_string(int(percentile(frameMs, 0.95) + 0.5)) + " ms; " + how + "; the process used " +
                        std::to_string(cores).substr(0, 4) + " cores"});
    rows.push_back({tag + ", input to its frame p95", percentile(inputWaitMs, 0.95), "ms", "",
                    "p50 " + std::to_string(int(percentile(inputWaitMs, 0.5) + 0.5)) +
                        " ms: a cursor move waits this long before a frame showing it (or a later move) starts"});
    rows.push_back({tag + ", frame loop per frame", mean(frameMs), "ms", "", stages});
    if (gpuPath) {
      // C(t) flattened into the GPU's program (PreviewSource::field): on the compile thread, or in
      // the frame (previews stage above) when it is cheap or a screenshot needs it.
      const uint64_t compiles = fields.onCompileThread + fields.onCallerThread;
      char where[200];
      std::snprintf(where, sizeof where,
                    "%llu on the compile thread (%.1f ms each), %llu on the UI thread (%.1f ms each), %llu superseded "
                    "before compiling",
                    (unsigned long long)fields.onCompileThread,
                    fields.onCompileThread ? fields.compileThreadMs / double(fields.onCompileThread) : 0.0,
                    (unsigned long long)fields.onCallerThread,
                    fields.onCallerThread ? fields.callerThreadMs / double(fields.onCallerThread) : 0.0,
                    (unsigned long long)fields.superseded);
      rows.push_back({tag + ", field compile", compiles ? (fields.compileThreadMs + fields.callerThreadMs) / double(compiles) : 0.0,
                      "ms", "", where});
    }
    rows.push_back({tag + ", new meshes shown while scrubbing", 1000.0 * double(shownWhileScrubbing) / scrubMs,
                    "fps", ">= 20 fps",
                    std::to_string(shownWhileScrubbing) + " of " + std::to_string(frameMs.size()) +
                        " frames drawn got their own mesh; " +
                        std::to_string(double(shownWhileScrubbing) / (cores * scrubMs / 1000.0)).substr(0, 4) +
                        " per second of the process's processor time (a shared machine's load moves the first figure)"});
    rows.push_back({tag + ", polygonisation p50", percentile(polyWhileScrubbing, 0.5), "ms", "",
                    "p95 " + std::to_string(int(percentile(polyWhileScrubbing, 0.95) + 0.5)) + " ms, per mesh shown"});
    rows.push_back({tag + ", settle at " + std::to_string(refined) + "^3 after scrubbing", refineMs, "ms", "",
                    std::to_string(settleFrames) + " frames; " + std::to_string(st.resolution) + "^3, " +
                        std::to_string(st.triangles) + " tris"});
  }
  return rows;
}

}  // namespace

ANIMORPH_BENCH("animorph-scrub",
               "editor preview pipeline scrubbing the dinosaur -> dragon animorphosis, CPU worker vs GPU (offscreen)",
               runAnimorphScrub);
