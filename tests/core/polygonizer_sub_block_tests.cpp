// The CPU polygoniser leaves out the interval tests of a block's remaining 4^3 sub-blocks once its
// first tested ones proved nothing (poly/sub_block_tests.h): the mesh must be the one every test
// gives, bit for bit, and the tests left out must be counted.
#include <catch2/catch.hpp>

#include <random>

#include "core/animorphosis/evaluate_generic.h"
#include "core/blobtree/compile.h"
#include "core/poly/polygonizer.h"
#include "core/poly/sub_block_tests.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;

namespace {

struct SubBlockRun {
  PolygonizeResult result;
  uint64_t skipped = 0;  // sub-block tests left out by this call
};

SubBlockRun polygonizeWith(const FieldProgram& p, PolygonizeSettings s, bool skipping) {
  setSubBlockTestSkipping(skipping);
  const uint64_t before = subBlockTestsSkippedTotal();
  auto r = polygonize(p, s);
  const uint64_t after = subBlockTestsSkippedTotal();
  setSubBlockTestSkipping(true);
  REQUIRE(r.ok());
  return {std::move(*r), after - before};
}

// The same mesh, bit for bit: positions, triangles, normals, colours.
void requireSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  CHECK(a.positions == b.positions);
  CHECK(a.indices == b.indices);
  CHECK(a.normals == b.normals);
  CHECK(a.colors == b.colors);
}

}  // namespace

TEST_CASE("sub-block tests left out: the demo's C(t) at 96^3 at three times is the mesh of every test, with most "
          "tests left out",
          "[polygonizer][animorph][demo]") {
  auto project = loadProject(std::string(ANIMORPH_SOURCE_DIR) + "/resources/demo/animorphosis.animorph");
  REQUIRE(project.ok());
  auto c = projectGenericTree(*project);
  REQUIRE(c.ok());
  const AnimorphosisTiming timing = animorphosisTiming(*project);
  for (double t : {2.8, 4.0, 5.2}) {
    const FieldProgram p = compileGeneric(*c, timing, t);
    PolygonizeSettings s;  // as the preview worker: 96^3, colours
    s.resolution = 96;
    s.colors = true;
    s.threads = 2;
    const SubBlockRun every = polygonizeWith(p, s, false);
    const SubBlockRun skipping = polygonizeWith(p, s, true);
    INFO("t = " << t << ": " << skipping.skipped << " sub-block tests left out of the "
                << 8 * every.result.stats.blocksEvaluated << " of the evaluated blocks; cells visited "
                << every.result.stats.cellsVisited << " with every test, " << skipping.result.stats.cellsVisited);
    REQUIRE(every.result.mesh.triangleCount() > 10000);
    CHECK(every.skipped == 0);
    // Most of the evaluated blocks' sub-blocks: their first two tests culled nothing.
    CHECK(skipping.skipped * 2 > 8 * every.result.stats.blocksEvaluated);
    CHECK(skipping.result.stats.cellsVisited >= every.result.stats.cellsVisited);
    requireSameMesh(skipping.result.mesh, every.result.mesh);
  }
}

TEST_CASE("sub-block tests left out: seeded random trees give the mesh of every test",
          "[polygonizer]") {
  uint64_t skippedTotal = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    const BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    for (double t : {0.0, 0.5}) {
      const FieldProgram p = compileFieldProgram(tree, t);
      PolygonizeSettings s;
      s.resolution = 48;
      Bounds b;
      b.add(glm::vec3(-1.2f));
      b.add(glm::vec3(1.2f));
      s.bounds = b;  // some trees are unbounded (e.g. a difference of nothing)
      s.colors = seed % 2 == 0;
      const SubBlockRun every = polygonizeWith(p, s, false);
      const SubBlockRun skipping = polygonizeWith(p, s, true);
      INFO("seed " << seed << " t " << t << ": " << skipping.skipped << " tests left out");
      CHECK(every.skipped == 0);
      requireSameMesh(skipping.result.mesh, every.result.mesh);
      skippedTotal += skipping.skipped;
    }
  }
  CHECK(skippedTotal > 0);
}
