// Auto-map against variants an artist could make of a tree (tests/util/tree_perturbation.h): per
// kind of change and for a mix, the share of the identity recovered and the share of wrong links,
// on the BlobTree demo creature, the animorphosis demo's dinosaur and dragon, and random trees.
#include <catch2/catch.hpp>

#include <cstdio>
#include <random>
#include <string>

#include "core/animorphosis/auto_correspond.h"
#include "core/animorphosis/generic_tree.h"
#include "core/animorphosis/validate_correspondence.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "core/field/field_program.h"
#include "demo/blob_creature.h"
#include "demo/dino_dragon.h"
#include "util/animorph_fixtures.h"
#include "util/tree_perturbation.h"

using namespace animorph;
using namespace animorph::test;

namespace {

struct KindTotals {
  double recovered = 0.0;  // summed over variants, weighted by the nodes scored
  int counted = 0, links = 0, wrong = 0, suggestions = 0, rightSuggestions = 0, edits = 0, unbuilt = 0;
  double share() const { return counted > 0 ? recovered / counted : 1.0; }
  double wrongShare() const { return links > 0 ? double(wrong) / links : 0.0; }
};

// Runs auto-map on `variants` variants of `a` per kind (and a mix of all kinds), prints a table
// and checks the rates: at least the target (95 % recovered, at most 1 % wrong) or, where a kind
// is held higher, the rate measured (docs/animorphosis.md, "Measured"), so a regression fails.
struct HeldRate {
  const char* kind;
  double recovered, wrong;
};

void checkPerturbations(const std::string& label, const BlobTree& a, int variants, unsigned seed, int edits,
                        std::vector<HeldRate> held = {}) {
  std::vector<std::vector<Perturbation>> kinds;
  std::vector<std::string> names;
  for (Perturbation p : allPerturbations()) {
    kinds.push_back({p});
    names.push_back(perturbationName(p));
  }
  kinds.push_back(allPerturbations());
  names.push_back("mix");
  std::printf("auto-map on %s (%zu nodes), %d variant(s) per kind:\n", label.c_str(), a.root.subtreeSize(), variants);
  for (size_t k = 0; k < kinds.size(); ++k) {
    KindTotals t;
    for (int v = 0; v < variants; ++v) {
      std::mt19937 rng(seed + unsigned(1000 * k + v));
      PerturbedTree b = perturbTree(a, kinds[k], edits, rng);
      REQUIRE(validateBlobTree(b.tree).ok());
      AutoCorrespondReport report;
      auto g = autoCorrespond(a, b.tree, {}, {}, &report);
      REQUIRE(g.ok());
      REQUIRE(validateCorrespondence(a, b.tree, *g).ok());
      RecoveryScore s = scoreRecovery(a, *g, b.identity);
      t.recovered += s.recovered * s.counted;
      t.counted += s.counted;
      t.links += s.links;
      t.wrong += s.wrongLinks;
      t.suggestions += s.suggestions;
      t.rightSuggestions += s.rightSuggestions;
      t.edits += b.edits;
      const auto generic = buildGenericTree(a, b.tree, *g);
      INFO(label << ", " << names[k] << ", variant " << v << ": " << (generic.ok() ? std::string() : generic.error()));
      CHECK(generic.ok());  // splits of convolution segments too: their pieces share the segment
      t.unbuilt += generic.ok() ? 0 : 1;
    }
    std::printf("  %-15s %4d edits: recovered %6.2f %%, wrong links %5.2f %% (%d of %d), suggestions %d (%d right), "
                "generic tree not built %d of %d\n",
                names[k].c_str(), t.edits, 100.0 * t.share(), 100.0 * t.wrongShare(), t.wrong, t.links,
                t.suggestions, t.rightSuggestions, t.unbuilt, variants);
    INFO(label << ", " << names[k] << ": recovered " << 100.0 * t.share() << " %, wrong " << 100.0 * t.wrongShare()
               << " % (" << t.wrong << " of " << t.links << ")");
    if (t.edits == 0) {  // nothing of that kind in this tree (the dragon has no segment to split)
      std::printf("  %-15s (nothing to change in this tree)\n", names[k].c_str());
      continue;
    }
    double minRecovered = 0.95, maxWrong = 0.01;
    for (const HeldRate& f : held)
      if (names[k] == f.kind) minRecovered = f.recovered, maxWrong = f.wrong;
    CHECK(t.share() >= minRecovered);
    CHECK(t.wrongShare() <= maxWrong);
  }
}

}  // namespace

TEST_CASE("animorphosis: auto-map recovers the identity through every kind of artist's change (demo creature, "
          "random trees)",
          "[animorph]") {
  // Held above the target where measured so: splits 98.0 %, drop / add 97.4 % (0.93 % wrong).
  checkPerturbations("the BlobTree demo creature", makeBlobCreature(), 8, 100, 3,
                     {{"split", 0.975, 0.0}, {"drop/add", 0.97, 0.01}});
  for (unsigned seed : {5u, 6u}) {
    std::mt19937 rng(seed);
    checkPerturbations("a random tree (seed " + std::to_string(seed) + ")", randomCreature(rng, 300), 3, 200 + seed,
                       8, {{"spline<->chain", 0.995, 0.0}});
  }
}

TEST_CASE("animorphosis: auto-map recovers the identity through every kind of artist's change (dinosaur, dragon)",
          "[animorph][demo]") {
  checkPerturbations("the dinosaur", makeDinosaur(), 1, 300, 30, {{"regroup", 0.995, 0.0}});
  checkPerturbations("the dragon", makeDragon(), 1, 400, 40);
}

TEST_CASE("animorphosis: auto-map finds the demo creature in a shuffled, renamed copy placed under an extra frame",
          "[animorph]") {
  BlobTree a = makeBlobCreature();
  std::mt19937 rng(32);
  std::unordered_map<int, int> idMap;
  BlobTree copy = perturbedCopy(a, {0.0f, 0.0f, 0.0f}, 1.0f, rng, idMap);
  BlobTree b;
  b.threshold = copy.threshold;
  b.root = makeBlobNode(NodeType::Frame, 90000, "scene_placement");
  b.root.vec3Param("translation") = Vec3Track(glm::vec3(2.5f, 0.0f, -1.5f));
  b.root.vec3Param("scale") = Vec3Track(glm::vec3(1.8f));
  std::function<void(BlobNode&)> rename = [&](BlobNode& n) {
    n.name = "copy_" + std::to_string(n.id);
    for (BlobNode& c : n.children) rename(c);
  };
  rename(copy.root);
  b.root.children.push_back(copy.root);
  REQUIRE(validateBlobTree(b).ok());
  AutoCorrespondReport report;
  auto g = autoCorrespond(a, b, {}, {}, &report);
  REQUIRE(g.ok());
  int right = 0;
  for (const auto& l : g->links) right += idMap.at(l.nodeA) == l.nodeB ? 1 : 0;
  const int parts = int(a.root.subtreeSize()) - 1;
  std::printf("wrapped copy of the demo creature: %d of %d links recovered (%d links, %d suggestions, mean confidence "
              "%.2f)\n",
              right, parts, int(g->links.size()), int(g->suggestions.size()), report.meanConfidence);
  CHECK(parts == 29);
  CHECK(right >= 28);
  CHECK(int(g->links.size()) - right <= 0);
  CHECK(buildGenericTree(a, b, *g).ok());
}

TEST_CASE("animorphosis: a convolution segment linked to the parts it was split into is cut into pieces that keep "
          "both fields",
          "[animorph]") {
  const BlobTree a = makeBlobCreature();
  int splitCopies = 0;
  for (unsigned seed = 0; seed < 6; ++seed) {
    std::mt19937 rng(700 + seed);
    PerturbedTree b = perturbTree(a, {Perturbation::Split}, 2, rng);
    // The identity as the graph: each split segment linked to its two or three parts.
    CorrespondenceGraph g;
    for (const auto& [idA, idsB] : b.identity)
      for (int idB : idsB) g.links.push_back({idA, idB, {}, 1.0f, false});
    REQUIRE(validateCorrespondence(a, b.tree, g).ok());
    auto c = buildGenericTree(a, b.tree, g);
    INFO("seed " << seed << ": " << (c.ok() ? std::string() : c.error()));
    REQUIRE(c.ok());
    splitCopies += c->splitCopies;
    // The pieces under their sum are the whole: A' is A, B' is B, at random points and times.
    const BlobTree a2 = genericSide(*c, MorphSide::A), b2 = genericSide(*c, MorphSide::B);
    std::uniform_real_distribution<float> x(-1.5f, 1.5f);
    std::uniform_real_distribution<double> time(0.0, 2.0);
    FieldEvaluator ev;
    double worst = 0.0;
    for (int k = 0; k < 8; ++k) {
      const double t = time(rng);
      // No cut-off of the segments' tails (at 1e-3 T each, three pieces would differ by 3e-3 T).
      CompileOptions exact;
      exact.cutoffEpsilon = 1e-9f;
      const FieldProgram pa = compileFieldProgram(a, t, exact), pa2 = compileFieldProgram(a2, t, exact);
      const FieldProgram pb = compileFieldProgram(b.tree, t, exact), pb2 = compileFieldProgram(b2, t, exact);
      for (int i = 0; i < 250; ++i) {
        const glm::vec3 p(x(rng), x(rng), x(rng));
        const double fa = ev.evaluatePoint(pa, p), fb = ev.evaluatePoint(pb, p);
        worst = std::max(worst, std::abs(ev.evaluatePoint(pa2, p) - fa) / std::max(std::abs(fa), double(pa.threshold)));
        worst = std::max(worst, std::abs(ev.evaluatePoint(pb2, p) - fb) / std::max(std::abs(fb), double(pb.threshold)));
      }
    }
    INFO("largest relative field difference " << worst);
    CHECK(worst <= 1e-4);
  }
  CHECK(splitCopies >= 6);  // every variant split something
}
