// Benchmarks on the animorphosis demo (dinosaur -> dragon): the generic tree's
// instantiate + flatten rate (and each stage alone), one 128^3 CPU polygonisation
// of the dragon, a bake of frames at 128^3, and consecutive frames polygonised
// with and without temporal coherence, each with a baseline measured in the same run.
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>

#include "animorph/evaluate_generic.h"
#include "blobtree/compile.h"
#include "cli/bench/bench.h"
#include "demo/animorphosis_demo.h"
#include "doc/animorphosis_project.h"
#include "poly/polygonizer.h"

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

// Triangles of one polygonisation at `resolution`, or -1 when it failed.
long polygonizeOnce(const FieldProgram& program, int resolution) {
  PolygonizeSettings s;
  s.resolution = resolution;
  auto r = polygonize(program, s);
  return r ? long(r->mesh.triangleCount()) : -1;
}

std::vector<Row> runDemoBench(const bench::Options& opt) {
  auto p = makeAnimorphosisDemoProject();
  if (!p) return {{"demo project failed: " + p.error(), 0.0, "", "", ""}};
  auto c = projectGenericTree(*p);
  if (!c) return {{"demo generic tree failed: " + c.error(), 0.0, "", "", ""}};
  const BlobTree& dino = p->actors[0].blobTree;
  const BlobTree& dragon = p->actors[1].blobTree;
  AnimorphosisTiming timing = animorphosisTiming(*p);
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  const double n = double(c->size());
  const int repeats = opt.quick ? 2 : 9;
  std::vector<Row> rows;
  std::string sizes = std::to_string(dino.root.subtreeSize()) + " -> " + std::to_string(dragon.root.subtreeSize()) +
                      " nodes, C " + std::to_string(c->size());

  double flat = bench::medianMs(repeats, [&] { (void)compileGeneric(*c, timing, mid); });
  rows.push_back({"instantiate + flatten C(t)", n / (flat * 1e-3), "nodes/s", ">= 1,000,000",
                  ms(flat) + " per frame; " + sizes});
  // Each stage alone: C(t) written into a kept snapshot, then that snapshot flattened.
  BlobTree kept;
  double t = kDemoMorphStartSec;
  double inst = bench::medianMs(repeats, [&] {
    t += 0.02;
    updateGenericSnapshot(*c, timing, t, kept);
  });
  rows.push_back({"stage: instantiate C(t) into the kept snapshot", n / (inst * 1e-3), "nodes/s", "", ms(inst)});
  FieldProgram flatProgram;
  double flatOnly = bench::medianMs(repeats, [&] { flatProgram = compileFieldProgram(kept, 0.0); });
  rows.push_back({"stage: flatten the snapshot", n / (flatOnly * 1e-3), "nodes/s", "",
                  ms(flatOnly) + ", " + std::to_string(flatProgram.primitiveCount()) + " primitives, " +
                      std::to_string(flatProgram.ops.size()) + " ops"});
  t = kDemoMorphStartSec;
  double scrub = bench::medianMs(repeats, [&] {
    t += 0.02;
    updateGenericSnapshot(*c, timing, t, kept);
    (void)compileFieldProgram(kept, 0.0);
  });
  rows.push_back({"update C(t) in place + flatten (scrubbing)", n / (scrub * 1e-3), "nodes/s", ">= 1,000,000",
                  ms(scrub) + " per frame"});
  double base = bench::medianMs(repeats, [&] { (void)compileFieldProgram(dragon, 0.5); });
  rows.push_back({"flatten the dragon alone (baseline)", double(dragon.root.subtreeSize()) / (base * 1e-3),
                  "nodes/s", "", ms(base) + " per frame"});

  const int res = opt.quick ? 48 : 128;
  FieldProgram dragonProgram = compileFieldProgram(dragon, 0.5);
  long tris = 0;
  double poly = bench::medianMs(opt.quick ? 1 : 3, [&] { tris = polygonizeOnce(dragonProgram, res); });
  double polyCpu = cpuMs([&] { (void)polygonizeOnce(dragonProgram, res); });
  rows.push_back({"polygonise the dragon at " + std::to_string(res) + "^3 (CPU)", poly, "ms", "<= 60 ms",
                  std::to_string(tris) + " triangles, " + std::to_string(dragonProgram.primitiveCount()) +
                      " primitives; processor time " + ms(polyCpu) + " (all threads)"});
  FieldProgram dinoProgram = compileFieldProgram(dino, 0.5);
  double polyDino = bench::medianMs(opt.quick ? 1 : 3, [&] { tris = polygonizeOnce(dinoProgram, res); });
  double polyDinoCpu = cpuMs([&] { (void)polygonizeOnce(dinoProgram, res); });
  rows.push_back({"polygonise the dinosaur at " + std::to_string(res) + "^3 (CPU, baseline)", polyDino, "ms", "",
                  std::to_string(tris) + " triangles, " + std::to_string(dinoProgram.primitiveCount()) +
                      " primitives; processor time " + ms(polyDinoCpu) + " (all threads)"});

  // A bake: frames spread over the interval, each instantiated, flattened and polygonised.
  const int frames = opt.quick ? 2 : 8;
  long bakeTris = 0;
  std::clock_t bakeClock = std::clock();
  double bake = bench::medianMs(0, [&] {
    bakeTris = 0;
    for (int f = 0; f < frames; ++f) {
      double tf = kDemoMorphStartSec + (kDemoMorphEndSec - kDemoMorphStartSec) * (f + 0.5) / frames;
      bakeTris += polygonizeOnce(compileGeneric(*c, timing, tf), res);
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

  // Temporal coherence: consecutive frames (1/24 s apart) on one grid, full sweeps against a
  // PolygonizeHistory; the meshes are compared.
  const int run = opt.quick ? 3 : 6;
  auto coherence = [&](const std::string& what, double firstSec) {
    std::vector<FieldProgram> programs;
    Bounds box;
    for (int f = 0; f < run; ++f) {
      programs.push_back(compileGeneric(*c, timing, firstSec + f / 24.0));
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
    size_t reused = 0, blocks = 0;
    double coherentMs = bench::medianMs(0, [&] {
      PolygonizeHistory history;
      PolygonizeSettings hs = ps;
      hs.history = &history;
      reused = blocks = 0;
      for (int f = 0; f < run; ++f)
        if (auto r = polygonize(programs[size_t(f)], hs)) {
          coherent[size_t(f)] = std::move(r->mesh);
          reused += r->stats.blocksReused;
          blocks += r->stats.blocksEvaluated;
        }
    });
    bool same = true;
    for (int f = 0; f < run; ++f)
      same &= full[size_t(f)].positions == coherent[size_t(f)].positions &&
              full[size_t(f)].normals == coherent[size_t(f)].normals &&
              full[size_t(f)].indices == coherent[size_t(f)].indices;
    std::string head = std::to_string(run) + " consecutive frames " + what + " at " + std::to_string(res) + "^3";
    rows.push_back({head + ", full sweeps (baseline)", fullMs / run, "ms/frame", "", ms(fullMs) + " in all"});
    rows.push_back({head + ", temporal coherence", coherentMs / run, "ms/frame", "",
                    ms(coherentMs) + " in all; " + std::to_string(reused) + " of " + std::to_string(blocks) +
                        " evaluated blocks reused; meshes " + (same ? "identical" : "DIFFER")});
  };
  coherence("of A before the morph", kDemoMorphStartSec - 1.0);
  coherence("of C(t) in the morph", mid);
  coherence("of B after the morph", kDemoMorphEndSec + 0.5);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("animorph-demo", "the dinosaur -> dragon demo: C(t) instantiate + flatten, 128^3 polygonisation, bake",
               runDemoBench);
