// Benchmarks on the animorphosis demo (dinosaur -> dragon): the generic tree's
// instantiate + flatten rate compiled directly (and through the snapshot, each stage alone), one 128^3 CPU polygonisation
// of the dragon, a bake of frames at 128^3, and consecutive frames polygonised
// with and without temporal coherence (exact, and within 0.1 cell: on the morph, on the dragon
// with only its wings moving, on the dinosaur with only its tail), a bake of consecutive frames
// on one grid with coherence, each with a baseline measured in the same run.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <functional>
#include <variant>
#include <memory>
#include <string>
#include <thread>

#include "core/animorphosis/compile_generic.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/blobtree/compile.h"
#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_hold_tracks.h"
#include "demo/animorphosis_demo.h"
#include "core/project/animorphosis_project.h"
#include "core/poly/frame_sequence.h"
#include "core/poly/polygonizer.h"
#include "core/poly/preview_polygonizer.h"
#include "core/scene/animorphosis_preview_source.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

std::string ms(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", v);
  return text;
}

// Processor time (all threads) of one run of fn, in ms: steadier than wall time on a loaded machine.
template <class Fn>
double cpuMs(Fn&& fn) {
  std::clock_t a = std::clock();
  fn();
  return 1e3 * double(std::clock() - a) / CLOCKS_PER_SEC;
}

constexpr float kToleranceCells = 0.1f;  // temporal coherence's tolerance in the rows below

// Every track of the tree held at its value at timeSec, except under nodes whose name starts with
// `moving` (their sub-trees keep their animation).
void holdNode(BlobNode& n, const std::string& moving, double timeSec) {
  if (n.name.rfind(moving, 0) == 0) return;
  for (ParamValue& v : n.params) {
    if (auto* f = std::get_if<FloatTrack>(&v)) *f = FloatTrack(f->evaluate(timeSec));
    else if (auto* x = std::get_if<Vec3Track>(&v)) *x = Vec3Track(x->evaluate(timeSec));
    else if (auto* q = std::get_if<QuatTrack>(&v)) *q = QuatTrack(q->evaluate(timeSec));
    else
      for (Vec3Track& p : std::get<ControlPoints>(v)) p = Vec3Track(p.evaluate(timeSec));
  }
  for (BlobNode& c : n.children) holdNode(c, moving, timeSec);
}

BlobTree holdAllBut(const BlobTree& tree, const std::string& moving, double timeSec) {
  BlobTree t = tree;
  t.threshold = FloatTrack(tree.threshold.evaluate(timeSec));
  holdNode(t.root, moving, timeSec);
  return t;
}

}  // namespace

// (bench_hold_tracks.h: shared with `bench gpu-coherence`)
animorph::BlobTree benchHoldAllBut(const animorph::BlobTree& tree, const std::string& moving, double timeSec) {
  return holdAllBut(tree, moving, timeSec);
}

namespace {

// Triangles of one polygonisation at `resolution`, or -1 when it failed. listsForSkeletal: per-sub-block
// primitive lists for skeletal primitives too (as before: the same mesh).
long polygonizeOnce(const FieldProgram& program, int resolution, bool listsForSkeletal = false) {
  PolygonizeSettings s;
  s.resolution = resolution;
  s.subBlockListsForSkeletal = listsForSkeletal;
  auto r = polygonize(program, s);
  return r ? long(r->mesh.triangleCount()) : -1;
}

// One run of the demo bench: the demo project, its generic tree C(t) and timing, and the rows so
// far. Each group of rows is one member function; runDemoBench calls them in the table's order.
struct DemoBench {
  DemoBench(const bench::Options& options, const Project& project, const GenericTree& tree)
      : opt(options), c(tree), dino(project.actors[0].blobTree), dragon(project.actors[1].blobTree),
        timing(animorphosisTiming(project)), n(double(tree.size())), repeats(options.quick ? 2 : 9),
        res(options.quick ? 48 : 128), compiler(tree) {
    compiler.keepValues(false);  // the rows' baselines evaluate every node every frame (as before 2026-11-30)
  }
  const bench::Options& opt;
  const GenericTree& c;
  const BlobTree& dino;
  const BlobTree& dragon;
  const AnimorphosisTiming timing;
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  const double n;     // nodes of C
  const int repeats;  // of each flatten measurement
  const int res;      // of the polygonisations and bakes
  GenericProgramCompiler compiler;  // C(t) -> FieldProgram directly (animorphosis/compile_generic.h), no kept values
  BlobTree kept;                    // the snapshot the baselines update in place
  std::vector<Row> rows;

  void flattenRows();
  void scrubFlattenRows();
  void refillRows();
  void polygoniseRows();
  void bakeRows();
  // Consecutive frames (1/24 s apart) of `frame` on one grid: full sweeps, temporal coherence
  // (exact, then within kToleranceCells), the meshes compared.
  void coherenceRows(const std::string& what, const std::function<FieldProgram(int)>& frame);
  void allCoherenceRows();
  void previewScrubRows();
  void sequenceBakeRows();
};

void DemoBench::flattenRows() {
  std::string sizes = std::to_string(dino.root.subtreeSize()) + " -> " + std::to_string(dragon.root.subtreeSize()) +
                      " nodes, C " + std::to_string(c.size());
  // C(t) -> FieldProgram: compiled directly (animorphosis/compile_generic.h: a compiler kept for C),
  // and the same program through the BlobTree snapshot (the baseline, measured in the same run).
  // A new program: everything it needs is built inside the timing (the compiler of C and the
  // program), one thread for the emitter plus the compiler's helper threads.
  FieldProgram direct;
  auto newProgram = [&] {
    GenericProgramCompiler fresh(c);
    FieldProgram program;
    fresh.compile(timing, mid, program);
    direct = std::move(program);
  };
  const double flat = bench::medianMs(repeats, newProgram);
  const double flatCpu = cpuMs([&] {
    for (int r = 0; r < repeats; ++r) newProgram();
  }) / repeats;
  // The same with the compiler kept from an earlier frame (the editor's case once C exists): a new program only.
  auto keptCompiler = [&] {
    FieldProgram fresh;
    compiler.compile(timing, mid, fresh);
  };
  const double flatKept = bench::medianMs(repeats, keptCompiler);
  const double flatKeptCpu = cpuMs([&] {
    for (int r = 0; r < repeats; ++r) keptCompiler();
  }) / repeats;
  double flatBase = bench::medianMs(repeats, [&] { (void)compileGeneric(c, timing, mid); });
  const std::string threads = std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " hardware threads";
  rows.push_back({"instantiate + flatten C(t), new compiler and program", n / (flat * 1e-3), "nodes/s", ">= 1,000,000",
                  ms(flat) + " wall per frame, processor time " + ms(flatCpu) + " (all threads; the emitter and its "
                  "helper threads on " + threads + "), median of " + std::to_string(repeats) + " after a warm-up; " +
                      sizes + " -> " + std::to_string(direct.primitiveCount()) + " primitives, " +
                      std::to_string(direct.ops.size()) + " ops"});
  rows.push_back({"  instantiate + flatten C(t), compiler kept, new program", n / (flatKept * 1e-3), "nodes/s", "",
                  ms(flatKept) + " wall per frame, processor time " + ms(flatKeptCpu) +
                      " (all threads); the compiler of C built once outside the timing"});
  rows.push_back({"  (baseline: snapshot + flatten)", n / (flatBase * 1e-3), "nodes/s", "", ms(flatBase) + " per frame"});
  // Each stage of the snapshot path alone: C(t) written into a kept snapshot, then that snapshot flattened.
  double t = kDemoMorphStartSec;
  double inst = bench::medianMs(repeats, [&] {
    t += 0.02;
    updateGenericSnapshot(c, timing, t, kept);
  });
  rows.push_back({"  stage (baseline): instantiate C(t) into the kept snapshot", n / (inst * 1e-3), "nodes/s", "",
                  ms(inst)});
  FieldProgram flatProgram;
  double flatOnly = bench::medianMs(repeats, [&] { flatProgram = compileFieldProgram(kept, 0.0); });
  rows.push_back({"  stage (baseline): flatten the snapshot", n / (flatOnly * 1e-3), "nodes/s", "",
                  ms(flatOnly) + ", " + std::to_string(flatProgram.primitiveCount()) + " primitives, " +
                      std::to_string(flatProgram.ops.size()) + " ops"});
}

// Scrubbing: consecutive times into one kept program, directly (each stage timed inside the
// compile) and through the snapshot updated in place.
void DemoBench::scrubFlattenRows() {
  double t = kDemoMorphStartSec;
  FieldProgram keptProgram;
  GenericProgramCompiler::Timing stages;
  int stageFrames = 0;
  auto scrubDirectFrame = [&] {
    t += 0.02;
    compiler.compile(timing, t, keptProgram);
    const GenericProgramCompiler::Timing& s = compiler.lastTiming();
    stages.typesSec += s.typesSec;
    stages.emitSec += s.emitSec;
    stages.finishSec += s.finishSec;
    ++stageFrames;
  };
  double scrub = bench::medianMs(repeats, scrubDirectFrame);
  const double scrubCpu = cpuMs([&] {
    for (int r = 0; r < repeats; ++r) scrubDirectFrame();
  }) / repeats;
  rows.push_back({"update C(t) + flatten into the kept program (scrubbing)", n / (scrub * 1e-3), "nodes/s",
                  ">= 1,000,000",
                  ms(scrub) + " per frame, compiled directly; processor time " + ms(scrubCpu) + " per frame (" +
                      std::to_string(long(n / (scrubCpu * 1e-3))) + " nodes/s)"});
  const double perFrame = 1e3 / std::max(1, stageFrames);
  rows.push_back({"  stage: the nodes' types at t", stages.typesSec * perFrame, "ms", "", "mean over the scrubbed frames"});
  rows.push_back({"  stage: emit ops and primitives", stages.emitSec * perFrame, "ms", "",
                  "the values evaluated meanwhile by helper threads, ahead of the emitter"});
  rows.push_back({"  stage: FieldProgram::finish", stages.finishSec * perFrame, "ms", "", ""});
  t = kDemoMorphStartSec;
  auto scrubKeptFrame = [&] {
    t += 0.02;
    updateGenericSnapshot(c, timing, t, kept);
    compileFieldProgram(kept, 0.0, keptProgram);
  };
  double scrubKept = bench::medianMs(repeats, scrubKeptFrame);
  const double scrubKeptCpu = cpuMs([&] {
    for (int r = 0; r < repeats; ++r) scrubKeptFrame();
  }) / repeats;
  rows.push_back({"  (baseline: snapshot updated in place + flatten into the kept program)", n / (scrubKept * 1e-3),
                  "nodes/s", "",
                  ms(scrubKept) + " per frame; processor time " + ms(scrubKeptCpu) + " per frame (" +
                      std::to_string(long(n / (scrubKeptCpu * 1e-3))) + " nodes/s)"});
  double base = bench::medianMs(repeats, [&] { (void)compileFieldProgram(dragon, 0.5); });
  rows.push_back({"flatten the dragon alone (baseline)", double(dragon.root.subtreeSize()) / (base * 1e-3),
                  "nodes/s", "", ms(base) + " per frame"});
}

// Scrubbing with C(t)'s structure kept (FieldProgram::beginRefill, GenericProgramCompiler::refill): the
// same frames (1/30 s apart from the middle of the morph) five ways, alternating A B C D E a frame each,
// each row the median of its frames: compiled into a kept program (A) and refilled into another (B);
// a new program per frame, compiled (C, the preview before), and a program from SharedGenericCompiler's
// pool refilled (D, the preview's sources now, values kept); E: B with the
// values of nodes whose inputs did not move kept (GenericProgramCompiler::keepValues), its own compiler.
void DemoBench::refillRows() {
  const int frames = opt.quick ? 6 : 24;
  FieldProgram keptA, keptB, keptE;
  GenericProgramCompiler keeping(c);  // values kept (the default)
  auto shared = std::make_shared<SharedGenericCompiler>(std::make_shared<const GenericTree>(c));
  std::vector<double> wall[5], cpu[5], finish[5];
  int outcomes[3] = {0, 0, 0};
  size_t evaluatedE = 0;
  compiler.refill(timing, mid, keptB);  // the structure the refills keep (a first compile)
  keeping.refill(timing, mid, keptE);
  { FieldProgram first; shared->compile(timing, mid, first); }
  for (int f = 0; f < frames; ++f) {
    const double t = mid + (f + 1) / 30.0;
    for (int way = 0; way < 5; ++way) {
      const auto w0 = std::chrono::steady_clock::now();
      const std::clock_t c0 = std::clock();
      FieldProgram fresh;
      if (way == 0) compiler.compile(timing, t, keptA);
      else if (way == 1) ++outcomes[int(compiler.refill(timing, t, keptB))];
      else if (way == 2) compiler.compile(timing, t, fresh);
      else if (way == 3) shared->compile(timing, t, *shared->takeProgram());  // pooled, let go at once
      else keeping.refill(timing, t, keptE);
      cpu[way].push_back(1e3 * double(std::clock() - c0) / CLOCKS_PER_SEC);
      wall[way].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - w0).count());
      if (way < 3) finish[way].push_back(1e3 * compiler.lastTiming().finishSec);
      if (way == 4) {
        finish[way].push_back(1e3 * keeping.lastTiming().finishSec);
        evaluatedE += keeping.lastEvaluatedNodes();
      }
    }
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  const SharedGenericCompiler::Counters n = shared->counters();
  const std::string how = "median of " + std::to_string(frames) + " frames 1/30 s apart, A B C D E alternated; the "
                          "emitter on this thread plus the compiler's helper threads; processor time ";
  rows.push_back({"scrub C(t): compile into the kept program (A, baseline)", median(wall[0]), "ms", "",
                  how + ms(median(cpu[0])) + ", FieldProgram::finish " + ms(median(finish[0]))});
  rows.push_back({"scrub C(t): refill the kept program's structure (B)", median(wall[1]), "ms", "",
                  how + ms(median(cpu[1])) + ", finishRefill " + ms(median(finish[1])) + "; " +
                      std::to_string(outcomes[int(RefillOutcome::Refilled)]) + " refilled, " +
                      std::to_string(outcomes[int(RefillOutcome::StructureChanged)]) + " structure changed"});
  rows.push_back({"scrub C(t): a new program per frame, compiled (C, baseline: the preview before)", median(wall[2]),
                  "ms", "", how + ms(median(cpu[2]))});
  rows.push_back({"scrub C(t): refill the kept program, unmoved nodes' values kept (E)", median(wall[4]), "ms", "",
                  how + ms(median(cpu[4])) + ", finishRefill " + ms(median(finish[4])) + "; nodes evaluated " +
                      std::to_string(evaluatedE / size_t(frames)) + " of " + std::to_string(keeping.nodeCount()) +
                      " a frame (A B C: all)"});
  // After the morph (B plays, s = 1 everywhere): B and E again, alternated, on frames 1/30 s apart.
  std::vector<double> afterWall[2], afterCpu[2];
  size_t afterEvaluated = 0;
  for (int f = 0; f < frames; ++f) {
    const double t = kDemoMorphEndSec + 0.5 + f / 30.0;
    for (int way = 0; way < 2; ++way) {
      const auto w0 = std::chrono::steady_clock::now();
      const std::clock_t c0 = std::clock();
      if (way == 0) compiler.refill(timing, t, keptB);
      else keeping.refill(timing, t, keptE);
      afterCpu[way].push_back(1e3 * double(std::clock() - c0) / CLOCKS_PER_SEC);
      afterWall[way].push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - w0).count());
      if (way == 1 && f > 0) afterEvaluated += keeping.lastEvaluatedNodes();
    }
  }
  const std::string after = "median of " + std::to_string(frames) + " frames 1/30 s apart from 0.5 s after the "
                            "morph, the two alternated; processor time ";
  rows.push_back({"scrub C(t) after the morph: refill, every node evaluated (B', baseline)", median(afterWall[0]), "ms",
                  "", after + ms(median(afterCpu[0]))});
  rows.push_back({"scrub C(t) after the morph: refill, unmoved nodes' values kept (E')", median(afterWall[1]), "ms",
                  "", after + ms(median(afterCpu[1])) + "; nodes evaluated " +
                          std::to_string(afterEvaluated / size_t(std::max(1, frames - 1))) + " of " +
                          std::to_string(keeping.nodeCount()) + " a frame"});
  const SharedGenericCompiler::PoolCounters pool = shared->poolCounters();
  rows.push_back({"scrub C(t): a pooled program per frame, refilled, values kept (D, the preview's sources)",
                  median(wall[3]), "ms", "",
                  how + ms(median(cpu[3])) + "; " + std::to_string(n.refills) + " refilled, " +
                      std::to_string(n.structureChanges) + " structure changed, " + std::to_string(n.firstCompiles) +
                      " first (outside the timing); programs from the pool: " + std::to_string(pool.reused) +
                      " reused, " + std::to_string(pool.made) + " made"});
}

void DemoBench::polygoniseRows() {
  long tris = 0;
  FieldProgram dragonProgram = compileFieldProgram(dragon, 0.5);
  double poly = bench::medianMs(opt.quick ? 1 : 3, [&] { tris = polygonizeOnce(dragonProgram, res); });
  double polyCpu = cpuMs([&] { (void)polygonizeOnce(dragonProgram, res); });
  rows.push_back({"polygonise the dragon at " + std::to_string(res) + "^3 (CPU)", poly, "ms", "<= 60 ms",
                  std::to_string(tris) + " triangles, " + std::to_string(dragonProgram.primitiveCount()) +
                      " primitives; processor time " + ms(polyCpu) + " (all threads)"});
  double polyLists = bench::medianMs(opt.quick ? 1 : 3, [&] { (void)polygonizeOnce(dragonProgram, res, true); });
  const double polyListsCpu = cpuMs([&] { (void)polygonizeOnce(dragonProgram, res, true); });
  rows.push_back({"  baseline: the same with per-sub-block lists (before)", polyLists, "ms", "",
                  "processor time " + ms(polyListsCpu) + " (all threads)"});
  FieldProgram dinoProgram = compileFieldProgram(dino, 0.5);
  double polyDino = bench::medianMs(opt.quick ? 1 : 3, [&] { tris = polygonizeOnce(dinoProgram, res); });
  double polyDinoCpu = cpuMs([&] { (void)polygonizeOnce(dinoProgram, res); });
  rows.push_back({"polygonise the dinosaur at " + std::to_string(res) + "^3 (CPU, baseline)", polyDino, "ms", "",
                  std::to_string(tris) + " triangles, " + std::to_string(dinoProgram.primitiveCount()) +
                      " primitives; processor time " + ms(polyDinoCpu) + " (all threads)"});
}

void DemoBench::bakeRows() {
  // A bake: frames spread over the interval, each instantiated, flattened and polygonised.
  const int frames = opt.quick ? 2 : 8;
  long bakeTris = 0;
  std::clock_t bakeClock = std::clock();
  double bake = bench::medianMs(0, [&] {
    bakeTris = 0;
    for (int f = 0; f < frames; ++f) {
      double tf = kDemoMorphStartSec + (kDemoMorphEndSec - kDemoMorphStartSec) * (f + 0.5) / frames;
      bakeTris += polygonizeOnce(compileGeneric(c, timing, tf), res);
    }
  });
  double bakeCpu = 0.5e3 * double(std::clock() - bakeClock) / CLOCKS_PER_SEC;  // two runs: warm-up and timed
  rows.push_back({"bake " + std::to_string(frames) + " frames of C(t) at " + std::to_string(res) + "^3",
                  bake / frames, "ms/frame", "100 frames <= 30 s",
                  ms(bake) + " in all, " + std::to_string(bakeTris / frames) + " triangles per frame; processor time " +
                      ms(bakeCpu / frames) + " per frame (all threads)"});
  double bakeDragon = bench::medianMs(0, [&] {
    for (int f = 0; f < frames; ++f)
      (void)polygonizeOnce(compileFieldProgram(dragon, double(f) / frames), res);
  });
  rows.push_back({"bake " + std::to_string(frames) + " frames of the dragon alone (baseline)", bakeDragon / frames,
                  "ms/frame", "", ms(bakeDragon) + " in all, spread over its loop"});
}

void DemoBench::coherenceRows(const std::string& what, const std::function<FieldProgram(int)>& frame) {
  const int run = opt.quick ? 3 : 6;
  std::vector<FieldProgram> programs;
  Bounds box;
  for (int f = 0; f < run; ++f) {
    programs.push_back(frame(f));
    box.add(programs.back().bounds());
  }
  PolygonizeSettings ps;
  ps.resolution = res;
  ps.bounds = box;
  std::vector<TriangleMesh> full(static_cast<size_t>(run)), coherent(static_cast<size_t>(run));
  double fullMs = bench::medianMs(0, [&] {
    for (int f = 0; f < run; ++f)
      if (auto r = polygonize(programs[size_t(f)], ps)) full[size_t(f)] = std::move(r->mesh);
  });
  // The frames in order with one history; the blocks reused and evaluated over all of them.
  auto withHistory = [&](float tolerance, std::vector<TriangleMesh>& meshes, size_t& reused, size_t& blocks) {
    return bench::medianMs(0, [&] {
      PolygonizeHistory history;
      PolygonizeSettings hs = ps;
      hs.history = &history;
      hs.reuseToleranceCells = tolerance;
      reused = blocks = 0;
      for (int f = 0; f < run; ++f)
        if (auto r = polygonize(programs[size_t(f)], hs)) {
          meshes[size_t(f)] = std::move(r->mesh);
          reused += r->stats.blocksReused;
          blocks += r->stats.blocksEvaluated;
        }
    });
  };
  size_t reused = 0, blocks = 0, reusedTol = 0, blocksTol = 0;
  double coherentMs = withHistory(0.0f, coherent, reused, blocks);
  bool same = true;
  for (int f = 0; f < run; ++f)
    same &= full[size_t(f)].positions == coherent[size_t(f)].positions &&
            full[size_t(f)].normals == coherent[size_t(f)].normals &&
            full[size_t(f)].indices == coherent[size_t(f)].indices;
  std::vector<TriangleMesh> tolerant(static_cast<size_t>(run));
  double tolerantMs = withHistory(kToleranceCells, tolerant, reusedTol, blocksTol);
  // The tolerant meshes have the full sweeps' triangles; how far their vertices are, in cells.
  bool sameTriangles = true;
  double deviation = 0.0;
  for (int f = 0; f < run; ++f) {
    const TriangleMesh &a = full[size_t(f)], &b = tolerant[size_t(f)];
    sameTriangles &= a.indices == b.indices && a.positions.size() == b.positions.size();
    for (size_t i = 0; i < a.positions.size() && i < b.positions.size(); ++i)
      deviation = std::max(deviation, double(glm::length(a.positions[i] - b.positions[i])));
  }
  auto grid = polygonizeGrid(programs[0], ps);
  const double cell = grid ? double(grid->cellSize) : 1.0;
  char dev[96];
  std::snprintf(dev, sizeof dev, "largest vertex deviation from the full sweeps %.4f cell", deviation / cell);
  std::string head = std::to_string(run) + " consecutive frames " + what + " at " + std::to_string(res) + "^3";
  rows.push_back({head + ", full sweeps (baseline)", fullMs / run, "ms/frame", "", ms(fullMs) + " in all"});
  rows.push_back({head + ", temporal coherence", coherentMs / run, "ms/frame", "",
                  ms(coherentMs) + " in all; " + std::to_string(reused) + " blocks reused (culled ones too), " +
                      std::to_string(blocks) + " evaluated; meshes " + (same ? "identical" : "DIFFER")});
  rows.push_back({head + ", coherence within 0.1 cell", tolerantMs / run, "ms/frame", "",
                  ms(tolerantMs) + " in all; " + std::to_string(reusedTol) + " blocks reused (culled ones too), " +
                      std::to_string(blocksTol) + " evaluated; triangles " + (sameTriangles ? "identical" : "DIFFER") + ", " + dev});
}

void DemoBench::allCoherenceRows() {
  auto generic = [&](double firstSec) {
    return [&, firstSec](int f) { return compileGeneric(c, timing, firstSec + f / 24.0); };
  };
  coherenceRows("of A before the morph", generic(kDemoMorphStartSec - 1.0));
  coherenceRows("of C(t) in the morph", generic(mid));
  coherenceRows("of B after the morph", generic(kDemoMorphEndSec + 0.5));
  // Only a part moves: the dragon with every track held at t = 0 but its wings' (flapping), and the
  // dinosaur with every track held but its tail's.
  const BlobTree wingsOnly = holdAllBut(dragon, "wing", 0.0), tailOnly = holdAllBut(dino, "tail", 0.0);
  coherenceRows("of the dragon, wings flapping, body held",
                [&](int f) { return compileFieldProgram(wingsOnly, 0.5 + f / 24.0); });
  coherenceRows("of the dinosaur, tail moving, body held",
                [&](int f) { return compileFieldProgram(tailOnly, 0.5 + f / 24.0); });
}

void DemoBench::previewScrubRows() {
  // Scrubbing C(t) on the CPU as the editor's preview worker does (poly/preview_polygonizer.h): each
  // frame's source (scene/animorphosis_preview_source.h) compiling C(t) directly and polygonising it
  // at 96^3, consecutive frames 1/24 s apart, with the worker's history (its grid kept while the
  // shape fits, 0.1 cell) against none.
  const int scrubFrames = opt.quick ? 3 : 12, scrubRes = opt.quick ? 48 : 96;
  auto shared = std::make_shared<SharedGenericCompiler>(std::make_shared<const GenericTree>(c));
  auto scrubbing = [&](bool coherent, size_t& reusedOut, int resolution) {
    PolygonizeHistory history;
    reusedOut = 0;
    return bench::medianMs(0, [&] {
      history.clear();
      reusedOut = 0;
      for (int f = 0; f < scrubFrames; ++f) {
        auto source = animorphosisPreviewSource(shared, timing, mid + f / 24.0);
        if (auto r = source->polygonize(resolution, 0, nullptr, coherent ? &history : nullptr))
          reusedOut += r->stats.blocksReused;
      }
    }) / scrubFrames;
  };
  size_t scrubReused = 0;
  const double scrubPlain = scrubbing(false, scrubReused, scrubRes);
  const double scrubCoherent = scrubbing(true, scrubReused, scrubRes);
  const std::string scrubHead = "scrub C(t) at " + std::to_string(scrubRes) + "^3 on the CPU (preview worker)";
  rows.push_back({scrubHead + ", no history (baseline)", 1e3 / scrubPlain, "fps", "", ms(scrubPlain) + " per frame"});
  rows.push_back({scrubHead + ", with its history", 1e3 / scrubCoherent, "fps", ">= 20 fps",
                  ms(scrubCoherent) + " per frame; " + std::to_string(scrubReused) + " blocks reused over " +
                      std::to_string(scrubFrames) + " frames"});
  // The same at coarser grids: what a preview that dropped to them while the slider is dragged
  // would show (the editor's preview answers at 96^3 first, then 128^3; it has no such level).
  for (int coarse : {64, 48}) {
    if (coarse >= scrubRes) continue;
    size_t reusedCoarse = 0;
    const double coarseMs = scrubbing(true, reusedCoarse, coarse);
    rows.push_back({"scrub C(t) at " + std::to_string(coarse) + "^3 on the CPU (preview worker), with its history",
                    1e3 / coarseMs, "fps", "", ms(coarseMs) + " per frame (a coarser grid than the editor's 96^3)"});
  }
}

void DemoBench::sequenceBakeRows() {
  // A bake with temporal coherence (poly/frame_sequence.h: one grid, 0.1 cell) against frames on
  // their own grids, consecutive frames of C(t) from the middle of the morph.
  const int bakeRun = opt.quick ? 3 : 12;
  std::vector<long> ownTris(size_t(bakeRun), 0);
  double ownMs = bench::medianMs(0, [&] {
    for (int f = 0; f < bakeRun; ++f) ownTris[size_t(f)] = polygonizeOnce(compileGeneric(c, timing, mid + f / 24.0), res);
  });
  size_t seqReused = 0, seqBlocks = 0;
  long seqTris = 0;
  std::string seqGrid;
  double seqMs = bench::medianMs(0, [&] {
    FrameSequenceSettings fs;
    fs.resolution = res;
    fs.reuseToleranceCells = kToleranceCells;
    seqTris = 0;
    auto st = polygonizeFrameSequence(
        bakeRun, [&](int f) { return compileGeneric(c, timing, mid + f / 24.0); },
        [&](int, PolygonizeResult&& r) -> Status {
          seqTris += long(r.mesh.triangleCount());
          return {};
        },
        fs);
    if (st) {
      seqReused = st->blocksReused;
      seqBlocks = st->blocksEvaluated;
      seqGrid = std::to_string(st->grid.cells[0]) + "x" + std::to_string(st->grid.cells[1]) + "x" +
                std::to_string(st->grid.cells[2]);
    }
  });
  long ownTotal = 0;
  for (long t : ownTris) ownTotal += t;
  std::string bakeHead = "bake " + std::to_string(bakeRun) + " consecutive frames of C(t) at " + std::to_string(res) + "^3";
  rows.push_back({bakeHead + ", each on its own grid (baseline)", ownMs / bakeRun, "ms/frame", "",
                  ms(ownMs) + " in all, " + std::to_string(ownTotal / bakeRun) + " triangles per frame"});
  rows.push_back({bakeHead + ", one grid + coherence within 0.1 cell", seqMs / bakeRun, "ms/frame", "100 frames <= 30 s",
                  ms(seqMs) + " in all (with the grid pass), " + std::to_string(seqTris / bakeRun) +
                      " triangles per frame on one " + seqGrid + " grid; " + std::to_string(seqReused) +
                      " blocks reused (culled ones too), " + std::to_string(seqBlocks) + " evaluated"});
}

std::vector<Row> runDemoBench(const bench::Options& opt) {
  auto p = makeAnimorphosisDemoProject();
  if (!p) return {{"demo project failed: " + p.error(), 0.0, "", "", ""}};
  auto c = projectGenericTree(*p);
  if (!c) return {{"demo generic tree failed: " + c.error(), 0.0, "", "", ""}};
  DemoBench b(opt, *p, *c);
  b.flattenRows();
  b.scrubFlattenRows();
  b.refillRows();
  b.polygoniseRows();
  b.bakeRows();
  b.allCoherenceRows();
  b.previewScrubRows();
  b.sequenceBakeRows();
  return std::move(b.rows);
}

}  // namespace

ANIMORPH_BENCH("animorph-demo", "the dinosaur -> dragon demo: C(t) instantiate + flatten, 128^3 polygonisation, bake",
               runDemoBench);

namespace {

// The demo's scrub C(t) rows alone (DemoBench::refillRows): the field compile per scrubbed frame,
// without the polygonisations and bakes of `bench animorph-demo` (minutes on 2 cores).
std::vector<Row> runScrubCompileBench(const bench::Options& opt) {
  auto p = makeAnimorphosisDemoProject();
  if (!p) return {{"demo project failed: " + p.error(), 0.0, "", "", ""}};
  auto c = projectGenericTree(*p);
  if (!c) return {{"demo generic tree failed: " + c.error(), 0.0, "", "", ""}};
  DemoBench b(opt, *p, *c);
  b.refillRows();
  return std::move(b.rows);
}

}  // namespace

ANIMORPH_BENCH("animorph-compile", "the demo's C(t) compiled per scrubbed frame: the scrub C(t) rows of animorph-demo",
               runScrubCompileBench);
