#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <functional>
#include <numeric>
#include <random>

#include "core/animorphosis/assignment.h"
#include "core/animorphosis/auto_correspond.h"
#include "core/animorphosis/generic_tree.h"
#include "core/animorphosis/validate_correspondence.h"
#include "demo/blob_creature.h"
#include "util/animorph_fixtures.h"

using namespace animorph;
using namespace animorph::test;

TEST_CASE("animorphosis: the assignment is the cheapest one", "[animorph]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  for (int rows = 1; rows <= 5; ++rows)
    for (int cols = 1; cols <= 5; ++cols) {
      std::vector<double> m(size_t(rows * cols));
      for (auto& v : m) v = u(rng);
      std::vector<int> got = minCostAssignment(m, rows, cols);
      double sum = 0.0;
      int assigned = 0;
      std::vector<int> used(size_t(cols), 0);
      for (int r = 0; r < rows; ++r)
        if (got[size_t(r)] >= 0) {
          sum += m[size_t(r * cols + got[size_t(r)])];
          ++assigned;
          REQUIRE(++used[size_t(got[size_t(r)])] == 1);
        }
      CHECK(assigned == std::min(rows, cols));
      // Brute force over column permutations.
      std::vector<int> perm(size_t(std::max(rows, cols)));
      std::iota(perm.begin(), perm.end(), 0);
      double best = 1e300;
      do {
        double s = 0.0;
        for (int r = 0; r < std::min(rows, cols); ++r)
          s += rows <= cols ? m[size_t(r * cols + perm[size_t(r)])] : m[size_t(perm[size_t(r)] * cols + r)];
        best = std::min(best, s);
      } while (std::next_permutation(perm.begin(), perm.end()));
      CHECK(sum == Approx(best).epsilon(1e-12));
    }
}

TEST_CASE("animorphosis: auto-map recovers a moved, rescaled, shuffled, jittered copy and keeps artist links",
          "[animorph]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    BlobTree a = randomCreature(rng, 400);
    std::unordered_map<int, int> idMap;
    BlobTree b = perturbedCopy(a, {3.0f, -1.0f, 0.5f}, 1.7f, rng, idMap, 0.03f);
    AutoCorrespondReport report;
    auto g = autoCorrespond(a, b, {}, {}, &report);
    REQUIRE(g.ok());
    REQUIRE(validateCorrespondence(a, b, *g).ok());
    double recovered = recoveredLinks(a, *g, idMap);
    INFO("seed " << seed << ": " << a.root.subtreeSize() << " nodes, " << g->links.size() << " links, recovered "
                 << recovered * 100.0 << "%, mean confidence " << report.meanConfidence);
    CHECK(recovered >= 0.95);
    CHECK(report.meanConfidence > 0.5);
    auto c = buildGenericTree(a, b, *g);
    INFO(c.error());
    CHECK(c.ok());
  }

  // Artist links stay as drawn, even deliberately "wrong" ones; automatic links are replaced.
  std::mt19937 rng(9);
  BlobTree a = randomCreature(rng, 200);
  std::unordered_map<int, int> idMap;
  BlobTree b = perturbedCopy(a, {0.0f, 2.0f, 0.0f}, 0.5f, rng, idMap);
  const BlobNode& first = a.root.children[0];
  const BlobNode& second = a.root.children[1];
  CorrespondenceGraph drawn;
  CorrespondenceLink swapped{first.id, idMap.at(second.id), hermiteRampTrack(2.0f, 0.0f), 1.0f, true};
  drawn.links.push_back(swapped);
  CorrespondenceLink stale{second.id, idMap.at(first.id), {}, 0.1f, false};
  drawn.links.push_back(stale);
  REQUIRE(validateCorrespondence(a, b, drawn).ok());
  AutoCorrespondReport report;
  auto g = autoCorrespond(a, b, drawn, {}, &report);
  REQUIRE(g.ok());
  CHECK(report.artistKept == 1);
  CHECK(report.automaticDropped == 1);
  REQUIRE(g->find(swapped.nodeA, swapped.nodeB) >= 0);
  CHECK(g->links[size_t(g->find(swapped.nodeA, swapped.nodeB))] == swapped);
  CHECK(g->linksOfA(first.id).size() == 1);
  CHECK(validateCorrespondence(a, b, *g).ok());
  CHECK(buildGenericTree(a, b, *g).ok());
}

TEST_CASE("animorphosis: auto-map between two different creatures gives a buildable graph", "[animorph]") {
  BlobTree a = walkerTree(), b = flyerTree();
  AutoCorrespondReport report;
  auto g = autoCorrespond(a, b, {}, {}, &report);
  REQUIRE(g.ok());
  std::string links;
  for (const auto& l : g->links) links += std::to_string(l.nodeA) + "->" + std::to_string(l.nodeB) + " (" + std::to_string(l.confidence) + ") ";
  INFO(links);
  CHECK(report.proposed >= 5);
  CHECK(g->find(2, 102) >= 0);  // body -> body
  CHECK(g->find(9, 112) >= 0);  // tail -> tail
  auto c = buildGenericTree(a, b, *g);
  INFO(c.error());
  CHECK(c.ok());
}

TEST_CASE("animorphosis: auto-map recovers the demo creature from a perturbed copy of itself", "[animorph]") {
  BlobTree a = makeBlobCreature();
  std::mt19937 rng(21);
  std::unordered_map<int, int> idMap;
  BlobTree b = perturbedCopy(a, {-2.0f, 0.3f, 1.0f}, 0.6f, rng, idMap, 0.01f);
  auto g = autoCorrespond(a, b, {}, {}, nullptr);
  REQUIRE(g.ok());
  double recovered = recoveredLinks(a, *g, idMap);
  INFO(a.root.subtreeSize() << " nodes, recovered " << recovered * 100.0 << "%");
  CHECK(recovered >= 0.95);
  auto c = buildGenericTree(a, b, *g);
  INFO(c.error());
  REQUIRE(c.ok());
  CHECK(c->splitCopies == 0);
  CHECK(c->nullPartners == 0);
}

TEST_CASE("animorphosis: auto-map reports its progress level by level, and a cancel stops it with no graph",
          "[animorph]") {
  const BlobTree a = walkerTree(), b = flyerTree();
  const double nodes = double(a.root.subtreeSize());
  AutoCorrespondSettings st;
  std::vector<std::pair<double, double>> calls;
  st.progress = [&](double done, double total) { calls.push_back({done, total}); };
  auto g = autoCorrespond(a, b, {}, st);
  REQUIRE(g.ok());
  REQUIRE(calls.size() >= 2);  // at least one level and the end
  for (size_t i = 0; i < calls.size(); ++i) {
    CHECK(calls[i].second == nodes);
    CHECK(calls[i].first <= calls[i].second);
    if (i > 0) CHECK(calls[i].first >= calls[i - 1].first);
  }
  CHECK(calls.back().first == nodes);
  // The same graph with and without progress.
  CHECK(*g == *autoCorrespond(a, b, {}, {}));

  // Cancelled before the first level: an error saying so, no progress past the start.
  std::atomic<bool> cancel{true};
  st.cancel = &cancel;
  calls.clear();
  auto cancelled = autoCorrespond(a, b, {}, st);
  REQUIRE_FALSE(cancelled.ok());
  CHECK(cancelled.error().find("cancelled") != std::string::npos);
  CHECK(calls.empty());
  // Cancelled after the second level: it stops there.
  cancel = false;
  st.progress = [&](double done, double total) {
    calls.push_back({done, total});
    if (calls.size() == 2) cancel = true;
  };
  cancelled = autoCorrespond(a, b, {}, st);
  REQUIRE_FALSE(cancelled.ok());
  CHECK(calls.size() == 2);
}
