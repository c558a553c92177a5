#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>

#include "blobtree/compile.h"
#include "poly/marching_cubes_table.h"
#include "poly/mesh_checks.h"
#include "poly/polygonizer.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;

namespace {

PolygonizeResult run(const FieldProgram& p, int res, bool cull = true) {
  PolygonizeSettings s;
  s.resolution = res;
  s.culling = cull;
  auto r = polygonize(p, s);
  REQUIRE(r.ok());
  return std::move(*r);
}

void requireClosedManifold(const TriangleMesh& m) {
  MeshTopology t = analyzeMesh(m);
  CHECK(t.boundaryEdges == 0);
  CHECK(t.nonManifoldEdges == 0);
  CHECK(t.misorientedEdges == 0);
  CHECK(t.nonManifoldVertices == 0);
  CHECK(t.degenerateTriangles == 0);
  CHECK(t.manifold());
}

// A creature-like chain of convolution segments.
BlobTree chain(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  glm::vec3 p(0.0f, 0.0f, -0.4f);
  for (int i = 0; i < n; ++i) {
    glm::vec3 q = p + 0.12f * glm::normalize(glm::vec3(u(rng), u(rng), 1.5f));
    root.children.push_back(convSegmentNode(2 + i, p, q, 0.04f + 0.02f * (u(rng) + 1.0f), 12.0f));
    p = q;
  }
  return treeOf(root, 1.0f);
}

}  // namespace

TEST_CASE("marching cubes table: every case closes its loops and has the complement's edges", "[polygonizer]") {
  const auto& t = marchingCubesTable();
  CHECK(t.triangleCount[0] == 0);
  CHECK(t.triangleCount[255] == 0);
  for (int mask = 1; mask < 255; ++mask) {
    // Every edge whose corners differ is used; no other edge is.
    for (int e = 0; e < 12; ++e) {
      bool crossing = ((mask >> t.edgeCorners[size_t(e)][0]) & 1) != ((mask >> t.edgeCorners[size_t(e)][1]) & 1);
      bool used = false;
      for (int q = 0; t.triangles[size_t(mask)][size_t(q)] != 255; ++q) used |= t.triangles[size_t(mask)][size_t(q)] == e;
      CHECK(crossing == used);
    }
  }
}

TEST_CASE("a sphere is a closed manifold of Euler characteristic 2 with the analytic volume", "[polygonizer]") {
  const float R = 0.5f, T = 0.5f;
  FieldProgram p = compileFieldProgram(treeOf(pointNode(1, {0.1f, -0.2f, 0.3f}, R), T), 0.0);
  PolygonizeResult r = run(p, 128);
  requireClosedManifold(r.mesh);
  MeshTopology t = analyzeMesh(r.mesh);
  CHECK(t.euler == 2);
  CHECK(t.components == 1);
  double rs = R * std::sqrt(1.0 - std::cbrt(double(T)));
  double exact = 4.0 / 3.0 * M_PI * rs * rs * rs;
  double vol = meshVolume(r.mesh);
  CHECK(vol > 0.0);  // outward orientation
  CHECK(std::abs(vol - exact) / exact < 0.01);
  // Vertices on the analytic sphere, normals radial and outward.
  double worst = 0.0, worstDot = 1.0;
  for (size_t i = 0; i < r.mesh.positions.size(); ++i) {
    glm::vec3 d = r.mesh.positions[i] - glm::vec3(0.1f, -0.2f, 0.3f);
    worst = std::max(worst, std::abs(glm::length(d) - rs));
    worstDot = std::min(worstDot, double(glm::dot(glm::normalize(d), r.mesh.normals[i])));
  }
  CHECK(worst < 0.5 * r.stats.cellSize);
  CHECK(worstDot > 0.99);
  CHECK(r.stats.orphanVertices == 0);
}

TEST_CASE("a circle primitive gives a torus: Euler characteristic 0, genus 1", "[polygonizer]") {
  FieldProgram p = compileFieldProgram(treeOf(circleNode(1, {0, 0, 0}, {0.3f, 1, 0.2f}, 0.4f, 0.25f), 0.5f), 0.0);
  PolygonizeResult r = run(p, 64);
  requireClosedManifold(r.mesh);
  MeshTopology t = analyzeMesh(r.mesh);
  CHECK(t.euler == 0);
  CHECK(t.components == 1);
  CHECK(t.genus() == 1);
}

TEST_CASE("two far blobs give two components", "[polygonizer]") {
  BlobNode root = operatorNode(NodeType::Blend, 1,
                               {pointNode(2, {-1, 0, 0}, 0.4f), pointNode(3, {1, 0.2f, 0}, 0.3f)});
  FieldProgram p = compileFieldProgram(treeOf(root), 0.0);
  PolygonizeResult r = run(p, 64);
  requireClosedManifold(r.mesh);
  MeshTopology t = analyzeMesh(r.mesh);
  CHECK(t.components == 2);
  CHECK(t.euler == 4);
}

TEST_CASE("culled polygonisation equals dense polygonisation", "[polygonizer]") {
  FieldProgram p = compileFieldProgram(chain(20, 7), 0.0);
  PolygonizeResult dense = run(p, 64, false);
  PolygonizeResult culled = run(p, 64, true);
  CHECK(culled.stats.blocksCulled > 0);
  CHECK(dense.stats.blocksCulled == 0);
  CHECK(culled.stats.pointsEvaluated < dense.stats.pointsEvaluated);
  REQUIRE(dense.mesh.triangleCount() > 500);
  CHECK(culled.mesh.positions == dense.mesh.positions);
  CHECK(culled.mesh.indices == dense.mesh.indices);
  CHECK(culled.mesh.normals == dense.mesh.normals);
  requireClosedManifold(culled.mesh);
  CHECK(analyzeMesh(culled.mesh).components == 1);
}

TEST_CASE("random animated trees polygonise to closed manifolds", "[polygonizer]") {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    for (double t : {0.0, 0.5}) {
      FieldProgram p = compileFieldProgram(tree, t);
      PolygonizeSettings s;
      s.resolution = 40;
      Bounds b;
      b.add(glm::vec3(-1.2f));
      b.add(glm::vec3(1.2f));
      s.bounds = b;  // some trees are unbounded (e.g. a difference of nothing)
      auto r = polygonize(p, s);
      REQUIRE(r.ok());
      INFO("seed " << seed << " t " << t);
      requireClosedManifold(r->mesh);
      s.culling = false;
      auto d = polygonize(p, s);
      REQUIRE(d.ok());
      CHECK(d->mesh.indices == r->mesh.indices);
    }
  }
}

TEST_CASE("polygonize: settings errors, cancel and progress", "[polygonizer]") {
  FieldProgram p = compileFieldProgram(treeOf(pointNode(1, {0, 0, 0}, 0.5f)), 0.0);
  PolygonizeSettings s;
  s.resolution = 1;
  CHECK_FALSE(polygonize(p, s).ok());
  s.resolution = 32;
  std::atomic<bool> cancel{true};
  s.cancel = &cancel;
  auto r = polygonize(p, s);
  REQUIRE(r.ok());
  CHECK(r->cancelled);
  CHECK(r->mesh.indices.empty());
  cancel = false;
  float last = -1.0f;
  bool monotone = true;
  s.progress = [&](float f) {
    monotone &= f >= last;
    last = f;
  };
  r = polygonize(p, s);
  REQUIRE(r.ok());
  CHECK_FALSE(r->cancelled);
  CHECK(last == 1.0f);
  CHECK(monotone);
}
