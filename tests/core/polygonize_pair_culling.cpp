// The polygoniser's middle culling level (pairs of 2x2x2 blocks culled by their interval,
// poly/polygonizer.cpp cullPairs): the same meshes as testing every block of a superblock one by
// one, and the blocks tested one by one growing with the surface (about 4x at twice the
// resolution), not with the volume. Counted through poly/polygonize_stage_times.h, never timed.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "core/blobtree/compile.h"
#include "core/poly/polygonize_stage_times.h"
#include "core/poly/polygonizer.h"
#include "util/blob_builders.h"
#include "util/morph_fixtures.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// A creature-like chain of n convolution segments (seeded), as in polygonizer.cpp's tests; radii
// times thick.
BlobTree segmentChain(int n, unsigned seed, float thick = 1.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  glm::vec3 p(0.0f, 0.0f, -0.4f);
  for (int i = 0; i < n; ++i) {
    glm::vec3 q = p + 0.12f * glm::normalize(glm::vec3(u(rng), u(rng), 1.5f));
    root.children.push_back(convSegmentNode(2 + i, p, q, thick * (0.04f + 0.02f * (u(rng) + 1.0f)), 12.0f));
    p = q;
  }
  return treeOf(root, 1.0f);
}

struct Counted {
  TriangleMesh mesh;
  PolygonizeStageTimes stages;
};

Counted polygonizeCounted(const FieldProgram& p, const PolygonizeSettings& s, bool pairCulling) {
  Counted c;
  setPolygonizeStageTimes(&c.stages);
  setPolygonizePairCulling(pairCulling);
  auto r = polygonize(p, s);
  setPolygonizePairCulling(true);
  setPolygonizeStageTimes(nullptr);
  REQUIRE(r.ok());
  c.mesh = std::move(r->mesh);
  return c;
}

void requireSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  REQUIRE(a.positions == b.positions);
  REQUIRE(a.indices == b.indices);
  REQUIRE(a.normals == b.normals);
  REQUIRE(a.colors == b.colors);
}

}  // namespace

TEST_CASE("pair culling: the same meshes as testing every block, fewer blocks tested", "[polygonizer][culling]") {
  // Seeded chains and random trees (with colours), at sizes whose grids end inside a pair.
  size_t fewer = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    const BlobTree tree = seed % 2 ? segmentChain(10 + int(seed) * 2, seed) : treeOf(randomNode(rng, 3, id), 0.5f);
    const FieldProgram p = compileFieldProgram(tree, 0.25 * seed);
    for (int res : {72, 100}) {
      PolygonizeSettings s;
      s.resolution = res;
      s.colors = seed % 4 == 1;
      Bounds b;
      b.add(glm::vec3(-1.2f));
      b.add(glm::vec3(1.2f));
      if (p.unbounded()) s.bounds = b;
      INFO("seed " << seed << " res " << res);
      const Counted with = polygonizeCounted(p, s, true), without = polygonizeCounted(p, s, false);
      requireSameMesh(with.mesh, without.mesh);
      CHECK(with.stages.blocksEvaluated <= without.stages.blocksEvaluated);
      CHECK(with.stages.blocksVisited <= without.stages.blocksVisited);
      fewer += with.stages.blocksVisited < without.stages.blocksVisited;
    }
  }
  CHECK(fewer >= 8);
}

TEST_CASE("pair culling: blocks tested one by one grow under 5x from 128^3 to 256^3 (about 6x without it)",
          "[polygonizer][culling]") {
  for (unsigned seed : {3u, 11u}) {
    const FieldProgram p = compileFieldProgram(segmentChain(24, seed, 3.0f), 0.0);
    PolygonizeSettings s;
    s.resolution = 128;
    const Counted lo = polygonizeCounted(p, s, true), loAll = polygonizeCounted(p, s, false);
    s.resolution = 256;
    const Counted hi = polygonizeCounted(p, s, true), hiAll = polygonizeCounted(p, s, false);
    requireSameMesh(hi.mesh, hiAll.mesh);
    const double tested = double(hi.stages.blocksVisited) / double(lo.stages.blocksVisited);
    const double testedAll = double(hiAll.stages.blocksVisited) / double(loAll.stages.blocksVisited);
    const double surface = double(hi.stages.blocksWithSurface) / double(lo.stages.blocksWithSurface);
    INFO("seed " << seed << ": blocks tested " << lo.stages.blocksVisited << " -> " << hi.stages.blocksVisited
                 << " (without pair culling " << loAll.stages.blocksVisited << " -> " << hiAll.stages.blocksVisited
                 << "), with surface " << lo.stages.blocksWithSurface << " -> " << hi.stages.blocksWithSurface);
    CHECK(surface < 4.8);
    CHECK(tested < 5.0);
    CHECK(tested < 0.85 * testedAll);
  }
}
