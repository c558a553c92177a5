// Benchmarks of the animorphosis core on a generic tree of several thousand
// nodes: building C, instantiating and flattening C(t) (against flattening A
// alone, the same run's baseline), automatic correspondence and the bake.
#include <chrono>
#include <cstdio>
#include <functional>

#include "core/animorphosis/auto_correspond.h"
#include "core/animorphosis/bake_keys.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/generic_tree.h"
#include "core/blobtree/compile.h"
#include "app/cli/bench/bench.h"
#include "demo/blob_creature.h"
#include "demo/dino_dragon.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

void renumber(BlobNode& n, int& next) {
  n.id = next++;
  for (BlobNode& c : n.children) renumber(c, next);
}

// A herd: `count` demo creatures on a grid `spacing` apart, each under its own frame.
BlobTree herd(int count, float spacing, int skipEvery) {
  BlobTree creature = makeBlobCreature();
  BlobTree t;
  t.threshold = creature.threshold;
  t.root = makeBlobNode(NodeType::Blend, 0, "herd");
  int side = 1;
  while (side * side < count) ++side;
  for (int i = 0; i < count; ++i) {
    if (skipEvery > 0 && i % skipEvery == skipEvery - 1) continue;
    BlobNode f = makeBlobNode(NodeType::Frame, 0, "member");
    f.vec3Param("translation") = Vec3Track(glm::vec3(spacing * float(i % side), 0.0f, spacing * float(i / side)));
    f.children.push_back(creature.root);
    t.root.children.push_back(std::move(f));
  }
  int next = 1;
  renumber(t.root, next);
  return t;
}

double secondsOf(const std::function<void()>& fn) {
  auto a = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

std::vector<Row> runAnimorphBench(const bench::Options& opt) {
  int count = opt.quick ? 20 : 240;
  BlobTree a = herd(count, 2.5f, 0);
  BlobTree b = herd(count, 3.0f, 10);  // every tenth creature missing: its parts shrink into neighbours
  std::vector<Row> rows;
  std::string sizes = std::to_string(a.root.subtreeSize()) + " -> " + std::to_string(b.root.subtreeSize()) + " nodes";

  Result<CorrespondenceGraph> g = Error{"not run"};
  double autoSec = secondsOf([&] { g = autoCorrespond(a, b, {}); });
  if (!g) return {{"auto-map failed: " + g.error(), 0.0, "", "", ""}};
  rows.push_back({"auto-map", autoSec * 1e3, "ms", "", sizes + ", " + std::to_string(g->links.size()) + " links"});
  // The animorphosis demo's creatures (2,278 and 7,044 nodes): each other, and the dragon itself.
  {
    BlobTree dino = makeDinosaur(), dragon = makeDragon();
    for (int self = 0; self < 2; ++self) {
      const BlobTree& from = self ? dragon : dino;
      Result<CorrespondenceGraph> d = Error{"not run"};
      AutoCorrespondReport rep;
      double sec = secondsOf([&] { d = autoCorrespond(from, dragon, {}, {}, &rep); });
      if (!d) return {{"auto-map of the demo failed: " + d.error(), 0.0, "", "", ""}};
      rows.push_back({self ? "auto-map, the demo's dragon -> itself" : "auto-map, the demo's dinosaur -> dragon",
                      sec * 1e3, "ms", "",
                      std::to_string(from.root.subtreeSize()) + " -> " + std::to_string(dragon.root.subtreeSize()) +
                          " nodes, " + std::to_string(rep.proposed) + " links, " + std::to_string(rep.suggested) +
                          " suggestions"});
    }
  }

  Result<GenericTree> c = Error{"not run"};
  double buildSec = secondsOf([&] { c = buildGenericTree(a, b, *g); });
  if (!c) return {{"generic tree failed: " + c.error(), 0.0, "", "", ""}};
  double n = double(c->size());
  rows.push_back({"build generic tree C", buildSec * 1e3, "ms", "",
                  std::to_string(c->size()) + " nodes, " + std::to_string(c->nullPartners) + " null partners"});

  AnimorphosisTiming timing;
  int repeats = opt.quick ? 3 : 15;
  double inst = bench::medianMs(repeats, [&] { (void)instantiateGeneric(*c, timing, 0.5); });
  rows.push_back({"instantiate C(t)", n / (inst * 1e-3), "nodes/s", "", std::to_string(inst) + " ms"});
  double flat = bench::medianMs(repeats, [&] { (void)compileGeneric(*c, timing, 0.5); });
  rows.push_back({"instantiate + flatten C(t)", n / (flat * 1e-3), "nodes/s", ">= 1,000,000",
                  std::to_string(flat) + " ms per frame"});
  BlobTree kept;
  double t = 0.0;
  double update = bench::medianMs(repeats, [&] {
    t += 0.01;
    updateGenericSnapshot(*c, timing, 0.2 + t, kept);
  });
  rows.push_back({"update C(t) in place", n / (update * 1e-3), "nodes/s", "", std::to_string(update) + " ms"});
  double scrub = bench::medianMs(repeats, [&] {
    t += 0.01;
    updateGenericSnapshot(*c, timing, 0.2 + t, kept);
    (void)compileFieldProgram(kept, 0.0);
  });
  rows.push_back({"update C(t) in place + flatten (scrubbing)", n / (scrub * 1e-3), "nodes/s", ">= 1,000,000",
                  std::to_string(scrub) + " ms per frame"});
  BlobTree atStart = instantiateGeneric(*c, timing, 0.0);
  double startFlat = bench::medianMs(repeats, [&] { (void)compileFieldProgram(atStart, 0.0); });
  rows.push_back({"flatten C(t0) = A (snapshot)", n / (startFlat * 1e-3), "nodes/s", "",
                  std::to_string(startFlat) + " ms per frame"});
  double base = bench::medianMs(repeats, [&] { (void)compileFieldProgram(a, 0.5); });
  rows.push_back({"flatten A(t) alone (baseline)", double(a.root.subtreeSize()) / (base * 1e-3), "nodes/s", "",
                  std::to_string(base) + " ms per frame"});

  BakedAnimorphosis baked;
  double bakeSec = secondsOf([&] { baked = bakeKeyframes(*c, timing); });
  rows.push_back({"key-frame bake", bakeSec * 1e3, "ms", "",
                  std::to_string(baked.report.keys) + " keys on " + std::to_string(baked.report.parameters) +
                      " channels, largest deviation " + std::to_string(baked.report.largestDeviation)});
  return rows;
}

}  // namespace

ANIMORPH_BENCH("animorph", "animorphosis of two herds of BlobTree creatures: auto-map, C, instantiate, bake",
               runAnimorphBench);
