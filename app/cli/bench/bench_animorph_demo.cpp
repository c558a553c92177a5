// Benchmarks on the animorphosis demo (dinosaur -> dragon): the generic tree's
// instantiate + flatten rate, one 128^3 CPU polygonisation of the dragon, and
// a bake of frames at 128^3, each with a baseline measured in the same run.
#include <cstdio>
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
  BlobTree kept;
  double t = kDemoMorphStartSec;
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
  rows.push_back({"polygonise the dragon at " + std::to_string(res) + "^3 (CPU)", poly, "ms", "<= 60 ms",
                  std::to_string(tris) + " triangles, " + std::to_string(dragonProgram.primitiveCount()) +
                      " primitives"});
  FieldProgram dinoProgram = compileFieldProgram(dino, 0.5);
  double polyDino = bench::medianMs(opt.quick ? 1 : 3, [&] { tris = polygonizeOnce(dinoProgram, res); });
  rows.push_back({"polygonise the dinosaur at " + std::to_string(res) + "^3 (CPU, baseline)", polyDino, "ms", "",
                  std::to_string(tris) + " triangles, " + std::to_string(dinoProgram.primitiveCount()) +
                      " primitives"});

  // A bake: frames spread over the interval, each instantiated, flattened and polygonised.
  const int frames = opt.quick ? 2 : 8;
  long bakeTris = 0;
  double bake = bench::medianMs(0, [&] {
    bakeTris = 0;
    for (int f = 0; f < frames; ++f) {
      double tf = kDemoMorphStartSec + (kDemoMorphEndSec - kDemoMorphStartSec) * (f + 0.5) / frames;
      bakeTris += polygonizeOnce(compileGeneric(*c, timing, tf), res);
    }
  });
  rows.push_back({"bake " + std::to_string(frames) + " frames of C(t) at " + std::to_string(res) + "^3",
                  bake / frames, "ms/frame", "100 frames <= 30 s",
                  ms(bake) + " in all, " + std::to_string(bakeTris / frames) + " triangles per frame"});
  double bakeDragon = bench::medianMs(0, [&] {
    for (int f = 0; f < frames; ++f)
      (void)polygonizeOnce(compileFieldProgram(dragon, double(f) / frames), res);
  });
  rows.push_back({"bake " + std::to_string(frames) + " frames of the dragon alone (baseline)", bakeDragon / frames,
                  "ms/frame", "", ms(bakeDragon) + " in all, spread over its loop"});
  return rows;
}

}  // namespace

ANIMORPH_BENCH("animorph-demo", "the dinosaur -> dragon demo: C(t) instantiate + flatten, 128^3 polygonisation, bake",
               runDemoBench);
