// Benchmark of the editor scrubbing the animorphosis demo (dinosaur -> dragon,
// resources/demo/animorphosis.animorph) through its interval, forward then
// back, through the editor's own pipeline: scene evaluation, the animorphosis'
// C(t) preview source (scene/animorphosis_scene.h: C compiled directly), the BlobTree previews at the
// interactive resolution (96^3; the CPU worker, then the GPU polygoniser), the
// renderer into an offscreen 1280x720 target (no window). A simulated cursor moves the playhead
// a timeline frame every 1/48 s. The CPU worker is measured twice: with the loop drawing a frame
// at once after each (as the editor did) and with the editor's scrub pacing (scene/scrub_pacing.h:
// a frame per new mesh, input at most once a paced interval, the worker on every hardware thread),
// and a third time paced with the kept viewport image (a frame whose scene did not change renders
// nothing).
// The frame loop never waits for a polygoniser, so two figures matter: frames per second of the
// loop, and new C(t) meshes shown per second while scrubbing (what the artist sees move); plus how
// long input waits for its frame, and how long the preview takes to settle at 128^3 once
// scrubbing stops.
#include <algorithm>
#include <optional>
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
#include "gpu/render/scene_fingerprint.h"
#include "gpu/frame/scene_from_frame.h"
#include "core/scene/animorphosis_scene.h"
#include "core/scene/scene_frame.h"
#include "core/scene/scrub_pacing.h"

namespace {

using namespace animorph;
using namespace animorph::bench;

// The demo and the frames a scrub visits.
struct ScrubDemo {
  Project project;
  std::string baseDir;
  std::vector<int> frames;  // the middle of the interval, a frame at a time, forward then back
  int mid = 0, span = 0, passes = 0;
  int interactive = 0, refined = 0;  // the previews' resolutions
  std::string actorId;               // C(t)'s actor
  Bounds view;                       // C(t)'s bounds at the middle: what the camera frames
  AssetCache assets;
  AnimorphosisCache cache;
};

// Loads the demo and picks the frames; returns why the bench is skipped, or empty.
std::string loadScrubDemo(const Options& opt, ScrubDemo& d) {
  namespace fs = std::filesystem;
  const fs::path demo = fs::path(ANIMORPH_SOURCE_DIR) / "resources/demo/animorphosis.animorph";
  auto project = loadProject(demo.string());
  if (!project) return project.error();
  if (!project->animorphosis.enabled()) return "the demo has no animorphosis";
  d.project = std::move(*project);
  d.baseDir = demo.parent_path().string();
  // The middle of the interval, a frame at a time (24 fps), forward then back.
  const Timeline& tl = d.project.timeline;
  const int f0 = int(tl.secToFrame(d.project.animorphosis.startSec) + 0.5),
            f1 = int(tl.secToFrame(d.project.animorphosis.endSec) + 0.5);
  d.span = opt.quick ? 4 : 24;
  const int mid = d.mid = (f0 + f1) / 2;
  d.passes = opt.quick ? 1 : 2;  // forward then back, twice: ~4 s of cursor moves
  for (int pass = 0; pass < d.passes; ++pass) {
    for (int f = mid - d.span + (pass > 0); f <= mid + d.span; ++f) d.frames.push_back(f);
    for (int f = mid + d.span - 1; f >= mid - d.span; --f) d.frames.push_back(f);
  }
  d.interactive = opt.quick ? 48 : 96, d.refined = opt.quick ? 64 : 128;
  return {};
}

// C(t)'s actor and bounds at the middle frame; returns why the bench is skipped, or empty.
std::string findMorphingActor(ScrubDemo& d) {
  SceneFrame frame = evaluateScene(d.project, d.baseDir, d.assets, d.project.timeline.frameToSec(d.mid));
  applyAnimorphosis(frame, d.project, d.cache, &d.project, 0);
  if (frame.blobs.empty() || !frame.blobs.front().source) return "no C(t) draw at the middle";
  d.actorId = frame.blobs.front().actorId;
  d.view = compileFieldProgram(*frame.blobs.front().ownTree(), 0.0).bounds();
  return {};
}

constexpr double kMovesPerSec = 48.0;  // the cursor: about the speed the unpaced loop scrubbed at here

struct ScrubMode {
  bool gpu, paced;
  const char* policy;
  // The editor's kept viewport image (gpu/present/viewport_image.h): a frame whose scene fingerprint
  // did not change renders nothing (the editor copies the kept image under its UI: not modelled here).
  bool keepImage = false;
};

// One mode's run: the editor's pipeline for a frame, and what the frames measured.
struct ScrubRun {
  ScrubDemo& d;
  OffscreenBench& off;
  const OrbitCamera& camera;
  ScrubMode mode;
  gpu::BlobPreviewSet previews;
  gpu::MeshCache meshes;
  gpu::BlobPreviewSettings ps;
  ScrubPacer pacer;
  bool paced = false;    // the previous frame paced the loop (the editor's viewport_frame: its threads)
  int scrubThreads = 0;  // the most polygoniser threads a scrubbing frame asked for
  std::vector<double> frameMs, polyMs, inputWaitMs;
  double stageMs[4] = {0, 0, 0, 0};  // evaluate the scene, C(t) into it, previews.update, draw
  std::string error;
  size_t meshesShown = 0;
  size_t scenePasses = 0;  // frames that rendered the scene (keepImage: the others kept the image)
  std::optional<uint64_t> keptFingerprint;
  gpu::ImplicitPreviewStatus last;

  ScrubRun(ScrubDemo& demo, OffscreenBench& o, const OrbitCamera& cam, ScrubMode m)
      : d(demo), off(o), camera(cam), mode(m), previews(*o.ctx), meshes(*o.ctx),
        ps{demo.interactive, demo.refined, interactivePreviewThreads(), m.gpu, false},
        pacer(ScrubPacer::intervalFor(demo.project.timeline.fps)) {}

  // Evaluates, previews and draws the scene at timeSec, counting a new mesh on screen.
  void oneFrame(double timeSec) {
    auto t = Clock::now();
    auto lap = [&](int stage) {
      stageMs[stage] += msSince(t);
      t = Clock::now();
    };
    SceneFrame frame = evaluateScene(d.project, d.baseDir, d.assets, timeSec);
    lap(0);
    applyAnimorphosis(frame, d.project, d.cache, &d.project, 0);
    lap(1);
    ps.threads = paced ? pacedPreviewThreads() : interactivePreviewThreads();
    previews.update(d.project, frame, ps);
    lap(2);
    gpu::Scene scene;
    gpu::buildScene(frame, d.project.view, {}, meshes, scene, &previews);
    const std::optional<uint64_t> fp = gpu::sceneFingerprint(scene, camera, off.width, off.height);
    if (!mode.keepImage || !fp || fp != keptFingerprint) {
      if (std::string e = off.render(camera, scene); !e.empty()) error = e;
      keptFingerprint = fp;
      ++scenePasses;
    }
    lap(3);
    meshes.endFrame();
    previews.endFrame();
    // A new mesh on screen: its polygonisation time or triangle count differs from the last one's.
    const gpu::ImplicitPreviewStatus st = previews.status(d.actorId);
    if (st.hasMesh && (st.milliseconds != last.milliseconds || st.triangles != last.triangles)) {
      ++meshesShown;
      polyMs.push_back(st.milliseconds);
    }
    last = st;
    if (!st.error.empty()) error = st.error;
  }

  double frameSec(int frame) const { return d.project.timeline.frameToSec(frame); }

  // Warm-up: the first shape (GPU pipelines compile, buffers grow), settled; then the counts restart.
  void warmUp() {
    const auto warm = Clock::now();
    oneFrame(frameSec(d.frames.front()));
    while (previews.busy() && msSince(warm) < 120000.0) {
      previews.waitIdle(1.0);
      oneFrame(frameSec(d.frames.front()));
    }
    meshesShown = 0;
    scenePasses = 0;
    polyMs.clear();
    for (double& m : stageMs) m = 0.0;
  }
};

// What the scrub itself measured (the settle after it apart).
struct ScrubFigures {
  double scrubMs = 0.0;
  double cores = 0.0;  // the process's processor time over the wall time
  std::string stages;  // the stages' mean times per scrubbing frame
  gpu::PreviewFieldCounters fields;
  size_t shownWhileScrubbing = 0;
  size_t scenePassesWhileScrubbing = 0;
  std::vector<double> polyWhileScrubbing;
  double refineMs = 0.0;
  int settleFrames = 0;
};

// The cursor moves a frame every 1/kMovesPerSec s; the loop draws frames as the editor does
// (paced or at once) until the cursor has passed every frame.
ScrubFigures scrub(ScrubRun& r) {
  ScrubFigures out;
  const gpu::PreviewFieldCounters fieldsBefore = r.previews.fieldCounters(r.d.actorId);
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
    if (moves >= r.d.frames.size()) break;
    // Every move since the last frame waited until this one (a skipped move too: a later one shows it).
    for (; shown <= moves; ++shown) r.inputWaitMs.push_back(1000.0 * (nowSec - double(shown) / kMovesPerSec));
    r.pacer.frameStarted(nowSec, moves, PreviewPolygonizer::publishedTotal());
    const auto t0 = Clock::now();
    r.oneFrame(r.frameSec(r.d.frames[moves]));
    r.frameMs.push_back(msSince(t0));
    r.scrubThreads = std::max(r.scrubThreads, r.ps.threads);
    // The editor's loop (app/editor/main.cpp): paced while the worker computes, else the next frame at once.
    r.paced = r.mode.paced && ScrubPacer::applies(true, r.previews.busy(), r.previews.needsFrames());
    for (double waitSec = 1.0; r.paced && waitSec > 0.0;) {
      const uint64_t seen = PreviewPolygonizer::publishedTotal();
      const size_t now = inputNow(nowSec);
      waitSec = r.pacer.waitSec(nowSec, now, seen);
      // Woken by a published mesh, or by the next cursor move (a window event in the editor).
      if (waitSec > 0.0)
        PreviewPolygonizer::waitForPublish(seen, std::min(waitSec, double(now + 1) / kMovesPerSec - nowSec));
    }
  }
  out.scrubMs = msSince(scrubStart);
  out.cores = 1000.0 * double(std::clock() - cpuStart) / CLOCKS_PER_SEC / out.scrubMs;
  char stages[160];
  const double n = double(r.frameMs.size());
  std::snprintf(stages, sizeof stages, "evaluate the scene %.1f, C(t) into it %.1f, previews %.1f, draw %.1f ms",
                r.stageMs[0] / n, r.stageMs[1] / n, r.stageMs[2] / n, r.stageMs[3] / n);
  out.stages = stages;
  out.fields = r.previews.fieldCounters(r.d.actorId);
  out.fields.onCompileThread -= fieldsBefore.onCompileThread;
  out.fields.onCallerThread -= fieldsBefore.onCallerThread;
  out.fields.compileThreadMs -= fieldsBefore.compileThreadMs;
  out.fields.callerThreadMs -= fieldsBefore.callerThreadMs;
  out.fields.superseded -= fieldsBefore.superseded;
  out.fields.prepareMs -= fieldsBefore.prepareMs;
  out.fields.refilled -= fieldsBefore.refilled;
  out.fields.firstCompiles -= fieldsBefore.firstCompiles;
  out.fields.structureChanged -= fieldsBefore.structureChanged;
  out.fields.notRefilled -= fieldsBefore.notRefilled;
  out.shownWhileScrubbing = r.meshesShown;
  out.scenePassesWhileScrubbing = r.scenePasses;
  out.polyWhileScrubbing = r.polyMs;
  return out;
}

// Scrubbing stops: frames keep coming until the refined mesh is on screen.
void settle(ScrubRun& r, ScrubFigures& out) {
  const auto stop = Clock::now();
  while (r.previews.busy() && msSince(stop) < 60000.0) {
    const uint64_t seen = PreviewPolygonizer::publishedTotal();
    r.oneFrame(r.frameSec(r.d.frames.back()));
    ++out.settleFrames;
    // Idle, the editor waits for the worker's next mesh (or its poll) instead of redrawing.
    if (r.mode.paced) PreviewPolygonizer::waitForPublish(seen, ScrubPacer::kMaxWaitSec);
  }
  out.refineMs = msSince(stop);
}

// C(t) flattened into the GPU's program (PreviewSource::field): on the compile thread, or in
// the frame (previews stage) when it is cheap or a screenshot needs it.
Row fieldCompileRow(const std::string& tag, const gpu::PreviewFieldCounters& fields) {
  const uint64_t compiles = fields.onCompileThread + fields.onCallerThread;
  char where[500];
  std::snprintf(where, sizeof where,
                "%llu on the compile thread (%.1f ms each), %llu on the UI thread (%.1f ms each), %llu superseded "
                "before compiling; each also prepared its GPU frame (grid bounds, packing, region lists: %.1f ms "
                "each, not in the row's figure); %llu refilled the kept structure (values only), %llu built it "
                "(%llu first, %llu structure changed), %llu not refillable",
                (unsigned long long)fields.onCompileThread,
                fields.onCompileThread ? fields.compileThreadMs / double(fields.onCompileThread) : 0.0,
                (unsigned long long)fields.onCallerThread,
                fields.onCallerThread ? fields.callerThreadMs / double(fields.onCallerThread) : 0.0,
                (unsigned long long)fields.superseded, compiles ? fields.prepareMs / double(compiles) : 0.0,
                (unsigned long long)fields.refilled,
                (unsigned long long)(fields.firstCompiles + fields.structureChanged),
                (unsigned long long)fields.firstCompiles, (unsigned long long)fields.structureChanged,
                (unsigned long long)fields.notRefilled);
  return {tag + ", field compile", compiles ? (fields.compileThreadMs + fields.callerThreadMs) / double(compiles) : 0.0,
          "ms", "", where};
}

// The rows of one mode's run.
void reportMode(const ScrubRun& r, const ScrubFigures& fig, const std::string& tag, std::vector<Row>& rows) {
  const gpu::ImplicitPreviewStatus st = r.previews.status(r.d.actorId);
  const std::vector<double>& frameMs = r.frameMs;
  const double scrubMs = fig.scrubMs, cores = fig.cores;
  std::string how = st.gpu ? "GPU" : "CPU, up to " + std::to_string(r.scrubThreads) + " threads";
  if (!st.gpuFallback.empty()) how += " (fell back: " + st.gpuFallback + ")";
  rows.push_back({tag + ", frame loop", 1000.0 * double(frameMs.size()) / scrubMs, "fps", "",
                  std::to_string(frameMs.size()) + " frames drawn; frame time p50 " +
                      std::to_string(int(percentile(frameMs, 0.5) + 0.5)) + " ms, p95 " +
                      std::to_string(int(percentile(frameMs, 0.95) + 0.5)) + " ms; " + std::to_string(fig.scenePassesWhileScrubbing) +
                      " rendered the scene" + (r.mode.keepImage ? " (the others kept the image)" : "") + "; " + how +
                      "; the process used " +
                      std::to_string(cores).substr(0, 4) + " cores"});
  rows.push_back({tag + ", input to its frame p95", percentile(r.inputWaitMs, 0.95), "ms", "",
                  "p50 " + std::to_string(int(percentile(r.inputWaitMs, 0.5) + 0.5)) +
                      " ms: a cursor move waits this long before a frame showing it (or a later move) starts"});
  rows.push_back({tag + ", frame loop per frame", mean(frameMs), "ms", "", fig.stages});
  if (r.mode.gpu) rows.push_back(fieldCompileRow(tag, fig.fields));
  const size_t shown = fig.shownWhileScrubbing;
  rows.push_back({tag + ", new meshes shown while scrubbing", 1000.0 * double(shown) / scrubMs, "fps", ">= 20 fps",
                  std::to_string(shown) + " of " + std::to_string(frameMs.size()) +
                      " frames drawn got their own mesh; " +
                      std::to_string(double(shown) / (cores * scrubMs / 1000.0)).substr(0, 4) +
                      " per second of the process's processor time (a shared machine's load moves the first figure)"});
  rows.push_back({tag + ", polygonisation p50", percentile(fig.polyWhileScrubbing, 0.5), "ms", "",
                  "p95 " + std::to_string(int(percentile(fig.polyWhileScrubbing, 0.95) + 0.5)) + " ms, per mesh shown"});
  rows.push_back({tag + ", settle at " + std::to_string(r.d.refined) + "^3 after scrubbing", fig.refineMs, "ms", "",
                  std::to_string(fig.settleFrames) + " frames; " + std::to_string(st.resolution) + "^3, " +
                      std::to_string(st.triangles) + " tris"});
}

std::vector<Row> runAnimorphScrub(const Options& opt) {
  std::vector<Row> rows;
  ScrubDemo d;
  if (std::string why = loadScrubDemo(opt, d); !why.empty()) return {{"skipped", 0, "", "", why}};
  OffscreenBench off;
  if (std::string why = off.create(); !why.empty()) return {{"skipped", 0, "", "", why}};
  if (std::string why = findMorphingActor(d); !why.empty()) return {{"skipped", 0, "", "", why}};
  rows.push_back({"device", 0, "", "",
                  off.ctx->deviceName() + "; " + std::to_string(d.frames.size()) + " frames " +
                      std::to_string(d.frames.front()) + ".." + std::to_string(d.frames.front() + 2 * d.span) + ".." +
                      std::to_string(d.frames.back()) + (d.passes > 1 ? " (twice)" : "") +
                      " of the animorphosis demo, 1280x720 offscreen; the cursor moves a frame every 1/48 s"});
  OrbitCamera camera;
  camera.frame(d.view, float(off.width) / float(off.height));
  for (const ScrubMode mode :
       {ScrubMode{false, false, ", redraw at once"}, ScrubMode{false, true, ", paced"},
        ScrubMode{false, true, ", paced, kept viewport image", true}, ScrubMode{true, false, ""}}) {
    if (mode.gpu && !opt.gpu && off.ctx->deviceType() == VK_PHYSICAL_DEVICE_TYPE_CPU) {
      rows.push_back({"GPU preview: skipped", 0, "", "", "a CPU Vulkan device (run with --gpu to measure it anyway)"});
      continue;
    }
    const std::string tag = std::string(mode.gpu ? "GPU" : "CPU") + " preview of C(t) at " +
                            std::to_string(d.interactive) + "^3" + mode.policy;
    ScrubRun run(d, off, camera, mode);
    run.warmUp();
    ScrubFigures fig = scrub(run);
    settle(run, fig);
    if (!run.error.empty()) {
      rows.push_back({tag + ": failed", 0, "", "", run.error});
      continue;
    }
    reportMode(run, fig, tag, rows);
  }
  return rows;
}

}  // namespace

ANIMORPH_BENCH("animorph-scrub",
               "editor preview pipeline scrubbing the dinosaur -> dragon animorphosis, CPU worker vs GPU (offscreen)",
               runAnimorphScrub);
