#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "core/blobtree/compile.h"
#include "core/poly/marching_cubes_table.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "util/blob_builders.h"
#include "util/manifold_checks.h"
#include "util/morph_fixtures.h"

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


// Faces of the unit cell holding edge e, as bits 2 * axis + side.
int edgeFaceBits(const MarchingCubesTable& t, int e) {
  const int c0 = t.edgeCorners[size_t(e)][0], c1 = t.edgeCorners[size_t(e)][1];
  int bits = 0;
  for (int a = 0; a < 3; ++a)
    if (((c0 >> a) & 1) == ((c1 >> a) & 1)) bits |= 1 << (2 * a + ((c0 >> a) & 1));
  return bits;
}

// Triangles of one cell case as directed edges between global edge-vertex
// keys; the cell's corner 0 sits at `offset` (integer lattice). A vertex key
// is the doubled midpoint of its grid edge, so neighbouring cells agree on it.
void appendCellEdges(const MarchingCubesTable& t, int mask, glm::ivec3 offset,
                     std::vector<std::pair<int, int>>& directed) {
  auto key = [&](int e) {
    glm::ivec3 m = 2 * offset;
    for (int c : {int(t.edgeCorners[size_t(e)][0]), int(t.edgeCorners[size_t(e)][1])})
      m += glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    return (m.z * 8 + m.y) * 8 + m.x;
  };
  const auto& tri = t.triangles[size_t(mask)];
  for (int q = 0; tri[size_t(q)] != 255; q += 3)
    for (int k = 0; k < 3; ++k) directed.push_back({key(tri[size_t(q + k)]), key(tri[size_t(q + (k + 1) % 3)])});
}

// Corner states of a lattice pattern.
enum class CornerState : uint8_t { Outside, Inside, OnSurface };

// A field over the integer lattice of the grid [0, n]^3 (cell size 1): a
// k = 3 point ball of radius 0.9 on every corner not Outside, intensity 2T
// (f = +T there) or T (f = 0 exactly there: the potential is exactly I at
// its centre). Balls do not reach the neighbouring corners, which keep
// f = -T, so the corner values are exactly +T, 0 or -T: ties everywhere.
FieldProgram latticeProgram(const std::vector<CornerState>& state, int n, float T) {
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  int id = 2;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const CornerState c = state[size_t((k * (n + 1) + j) * (n + 1) + i)];
        if (c == CornerState::Outside) continue;
        root.children.push_back(pointNode(id++, glm::vec3(float(i), float(j), float(k)), 0.9f,
                                          c == CornerState::Inside ? 2.0f * T : T));
      }
  return compileFieldProgram(treeOf(root, T), 0.0);
}

// Polygonises a lattice program on [0, nx] x [0, ny] x [0, nz] with cell size 1.
PolygonizeResult runLattice(const FieldProgram& p, glm::ivec3 n, bool cull) {
  PolygonizeSettings s;
  s.resolution = std::max({n.x, n.y, n.z});
  s.culling = cull;
  Bounds b;
  b.add(glm::vec3(0.0f));
  b.add(glm::vec3(n));
  s.bounds = b;
  auto r = polygonize(p, s);
  REQUIRE(r.ok());
  REQUIRE(r->stats.cellSize == 1.0f);
  return std::move(*r);
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

TEST_CASE("marching cubes table: no cell draws a diagonal between two edges of one face", "[polygonizer]") {
  // Such a diagonal lies in the face the cell shares with its neighbour, which
  // may draw it too: four triangles on one edge.
  const auto& t = marchingCubesTable();
  for (int mask = 1; mask < 255; ++mask) {
    INFO("case " << mask);
    std::vector<std::pair<int, int>> undirected;
    const auto& tri = t.triangles[size_t(mask)];
    for (int q = 0; tri[size_t(q)] != 255; q += 3) {
      const int e[3] = {tri[size_t(q)], tri[size_t(q + 1)], tri[size_t(q + 2)]};
      // No triangle lies in a face plane (it would be flat on the shared face).
      CHECK((edgeFaceBits(t, e[0]) & edgeFaceBits(t, e[1]) & edgeFaceBits(t, e[2])) == 0);
      for (int k = 0; k < 3; ++k) undirected.push_back(std::minmax(e[k], e[(k + 1) % 3]));
    }
    std::sort(undirected.begin(), undirected.end());
    for (size_t i = 0; i + 1 < undirected.size(); ++i) {
      if (undirected[i] != undirected[i + 1]) continue;  // used once: a crossing of a face
      INFO("diagonal " << undirected[i].first << "-" << undirected[i].second);
      CHECK((edgeFaceBits(t, undirected[i].first) & edgeFaceBits(t, undirected[i].second)) == 0);
    }
  }
}

TEST_CASE("marching cubes table: two cells sharing a face give a manifold, consistently oriented pair", "[polygonizer]") {
  // Exhaustive: every case of the low cell, every sign pattern of the high
  // cell's far face, along each axis. Every edge gets at most two triangles,
  // running opposite ways along it.
  const auto& t = marchingCubesTable();
  std::vector<std::pair<int, int>> directed;
  std::vector<std::pair<std::pair<int, int>, int>> undirected;
  size_t bad = 0, pairs = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int low = 0; low < 256; ++low)
      for (int far = 0; far < 16; ++far) {
        int high = 0;
        for (int c = 0, f = 0; c < 8; ++c) {
          const bool inside = (c >> axis) & 1 ? (far >> f++) & 1 : (low >> (c | (1 << axis))) & 1;
          high |= int(inside) << c;
        }
        directed.clear();
        appendCellEdges(t, low, glm::ivec3(0), directed);
        glm::ivec3 up(0);
        up[axis] = 1;
        appendCellEdges(t, high, up, directed);
        undirected.clear();
        for (auto [a, b] : directed) undirected.push_back({std::minmax(a, b), a < b ? 1 : -1});
        std::sort(undirected.begin(), undirected.end());
        bool ok = true;
        for (size_t i = 0; i < undirected.size();) {
          size_t j = i;
          int sense = 0;
          while (j < undirected.size() && undirected[j].first == undirected[i].first) sense += undirected[j++].second;
          ok &= j - i == 1 || (j - i == 2 && sense == 0);
          i = j;
        }
        bad += !ok;
        ++pairs;
        if (!ok) UNSCOPED_INFO("axis " << axis << ": cases " << low << " | " << high);
      }
  CHECK(pairs == 3 * 256 * 16);
  CHECK(bad == 0);
}

TEST_CASE("an ambiguous face shared by two cells gets one surface, not a triangle from each side", "[polygonizer]") {
  // Corner signs of the two cells (5, 5, 13) and (5, 5, 14) of the space-time
  // morph of the demo at frame 75, 24^3, where the mesh had two non-manifold
  // edges. Values (x fastest, then y), per z layer:
  //   z = 13:  0.3596  0.2608  0.3158  0.2574   all inside
  //   z = 14:  0.0399 -0.0102 -0.0465  0.1055   ambiguous face: diagonal corners inside
  //   z = 15:  0.2263  0.1225  0.2586  0.2478   all inside
  // Cases 159 (below) and 249 (above): each cell's loop crosses the shared face
  // twice, and both used to fan it with a triangle lying flat in that face, the
  // same triangle with opposite windings.
  const float T = 0.5f;
  const glm::ivec3 n(3, 3, 4);
  std::vector<CornerState> state(size_t(5 * 5 * 5), CornerState::Outside);
  auto at = [&](int i, int j, int k) -> CornerState& { return state[size_t((k * 5 + j) * 5 + i)]; };
  const float values[3][4] = {{0.3596f, 0.2608f, 0.3158f, 0.2574f},
                              {0.0399f, -0.0102f, -0.0465f, 0.1055f},
                              {0.2263f, 0.1225f, 0.2586f, 0.2478f}};
  for (int z = 0; z < 3; ++z)
    for (int c = 0; c < 4; ++c)
      if (values[z][c] >= 0.0f) at(1 + (c & 1), 1 + (c >> 1), 1 + z) = CornerState::Inside;
  const FieldProgram p = latticeProgram(state, 4, T);
  auto caseOf = [&](int k0) {
    int mask = 0;
    for (int c = 0; c < 8; ++c)
      if (test::fieldAt(p, glm::vec3(float(1 + (c & 1)), float(1 + ((c >> 1) & 1)), float(k0 + (c >> 2)))) >= 0.0f)
        mask |= 1 << c;
    return mask;
  };
  REQUIRE(caseOf(1) == 159);
  REQUIRE(caseOf(2) == 249);
  const PolygonizeResult culled = runLattice(p, n, true);
  const PolygonizeResult dense = runLattice(p, n, false);
  requireClosedManifold(culled.mesh);
  const MeshTopology topo = analyzeMesh(culled.mesh);
  CHECK(topo.components == 1);
  // Two inside slabs joined by the two inside pillars at the diagonal corners of
  // the ambiguous face: a ring, genus 1.
  CHECK(topo.euler == 0);
  CHECK(topo.genus() == 1);
  CHECK(meshVolume(culled.mesh) > 0.0);
  CHECK(culled.mesh.indices == dense.mesh.indices);
}

TEST_CASE("random lattice patterns with ties and exact zeros polygonise to closed manifolds", "[polygonizer]") {
  // Random corner signs, every corner value exactly +T, 0 or -T; the grid is
  // 6^3 cells of size 1, the outer corners forced outside by the polygoniser.
  const float T = 0.5f;
  const int n = 6;
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  size_t zeros = 0, surfaces = 0;
  for (int pattern = 0; pattern < 120; ++pattern) {
    const float pIn = 0.2f + 0.6f * u(rng), pZero = pattern % 3 == 0 ? 0.0f : 0.3f * u(rng);
    std::vector<CornerState> state(size_t((n + 1) * (n + 1) * (n + 1)), CornerState::Outside);
    for (int k = 1; k < n; ++k)
      for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) {
          const float r = u(rng);
          state[size_t((k * (n + 1) + j) * (n + 1) + i)] =
              r < pZero ? CornerState::OnSurface : r < pZero + pIn ? CornerState::Inside : CornerState::Outside;
        }
    const FieldProgram p = latticeProgram(state, n, T);
    // The zeros are exact (the whole point of the pattern).
    for (int k = 1; k < n; ++k)
      for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i)
          if (state[size_t((k * (n + 1) + j) * (n + 1) + i)] == CornerState::OnSurface) {
            const float f = test::fieldAt(p, glm::vec3(float(i), float(j), float(k)));
            if (f != 0.0f) FAIL("corner value " << f << " is not exactly 0");
            ++zeros;
          }
    const PolygonizeResult culled = runLattice(p, glm::ivec3(n), true);
    const PolygonizeResult dense = runLattice(p, glm::ivec3(n), false);
    INFO("pattern " << pattern);
    const MeshTopology topo = analyzeMesh(culled.mesh);
    if (!topo.manifold() || topo.degenerateTriangles != 0) requireClosedManifold(culled.mesh);  // reports which
    CHECK(culled.mesh.indices == dense.mesh.indices);
    CHECK(culled.stats.orphanVertices == 0);
    surfaces += culled.mesh.triangleCount() > 0;
  }
  CHECK(zeros > 500);
  CHECK(surfaces == 120);
}

TEST_CASE("many small random trees polygonise to closed manifolds on shifted coarse grids", "[polygonizer]") {
  std::uniform_real_distribution<float> u(-0.15f, 0.15f);
  for (unsigned seed = 100; seed < 160; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    const BlobTree tree = treeOf(randomNode(rng, 2 + int(seed % 2), id), 0.5f);
    const FieldProgram p = compileFieldProgram(tree, 0.25);
    PolygonizeSettings s;
    s.resolution = 10 + int(seed % 7);
    Bounds b;
    b.add(glm::vec3(-1.2f) + glm::vec3(u(rng), u(rng), u(rng)));
    b.add(glm::vec3(1.2f) + glm::vec3(u(rng), u(rng), u(rng)));
    s.bounds = b;
    auto r = polygonize(p, s);
    REQUIRE(r.ok());
    INFO("seed " << seed);
    const MeshTopology topo = analyzeMesh(r->mesh);
    if (!topo.manifold() || topo.degenerateTriangles != 0) requireClosedManifold(r->mesh);
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
