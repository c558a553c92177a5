#include <catch2/catch.hpp>

// The mesh checkers behind the polygoniser, morph and demo tests (analyzeMesh in core,
// closedManifoldDefects / requireClosedManifold and weldedTopology in tests/util) shown meshes
// that are NOT closed manifolds: each defect must be found, named and counted, so a test that
// relies on a checker cannot pass because the checker sees nothing.
#include <cmath>
#include <string>
#include <vector>

#include "core/poly/mesh_checks.h"
#include "util/manifold_checks.h"
#include "util/mesh_checks.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// A tetrahedron, counter-clockwise seen from outside (outward normals, volume +1/6).
TriangleMesh tetrahedron(glm::vec3 offset = glm::vec3(0.0f)) {
  TriangleMesh m;
  m.positions = {offset + glm::vec3(0, 0, 0), offset + glm::vec3(1, 0, 0), offset + glm::vec3(0, 1, 0),
                 offset + glm::vec3(0, 0, 1)};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

// b's triangles appended to a, b's indices shifted past a's vertices.
TriangleMesh joined(TriangleMesh a, const TriangleMesh& b) {
  const uint32_t base = static_cast<uint32_t>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (uint32_t i : b.indices) a.indices.push_back(base + i);
  return a;
}

// A torus of n x n quads (two triangles each), outward: genus 1.
TriangleMesh torus(int n) {
  TriangleMesh m;
  const float kPi = 3.14159265f;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float u = 2.0f * kPi * i / n, v = 2.0f * kPi * j / n;
      m.positions.push_back({(1.0f + 0.3f * std::cos(v)) * std::cos(u), (1.0f + 0.3f * std::cos(v)) * std::sin(u),
                             0.3f * std::sin(v)});
    }
  auto at = [n](int i, int j) { return static_cast<uint32_t>(((i + n) % n) * n + (j + n) % n); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  return m;
}

// Every triangle with its own three vertices (as a triangle soup from a file): only welding by
// position recovers the connectivity.
TriangleMesh unwelded(const TriangleMesh& m) {
  TriangleMesh s;
  for (uint32_t i : m.indices) {
    s.indices.push_back(static_cast<uint32_t>(s.positions.size()));
    s.positions.push_back(m.positions[i]);
  }
  return s;
}

}  // namespace

TEST_CASE("mesh checker: a tetrahedron and a torus are closed manifolds of genus 0 and 1", "[mesh_checks]") {
  const TriangleMesh tet = tetrahedron();
  const MeshTopology t = analyzeMesh(tet);
  CHECK(t.vertices == 4);
  CHECK(t.edges == 6);
  CHECK(t.faces == 4);
  CHECK(t.euler == 2);
  CHECK(t.components == 1);
  CHECK(t.genus() == 0);
  CHECK(t.manifold());
  CHECK(t.degenerateTriangles == 0);
  CHECK(meshVolume(tet) == Approx(1.0 / 6.0));
  CHECK(closedManifoldDefects(tet).empty());

  const TriangleMesh ring = torus(12);
  const MeshTopology r = analyzeMesh(ring);
  CHECK(r.euler == 0);
  CHECK(r.genus() == 1);
  CHECK(r.manifold());
  CHECK(closedManifoldDefects(ring).empty());
  CHECK(meshVolume(ring) > 0.0);
}

TEST_CASE("mesh checker: a missing face leaves three boundary edges, not watertight", "[mesh_checks]") {
  TriangleMesh open = tetrahedron();
  open.indices.resize(9);
  const MeshTopology t = analyzeMesh(open);
  CHECK(t.boundaryEdges == 3);
  CHECK_FALSE(t.watertight());
  CHECK_FALSE(t.manifold());
  const std::string d = closedManifoldDefects(open);
  CHECK_THAT(d, Catch::Contains("3 boundary edges"));
  const Topology w = weldedTopology(unwelded(open).positions, unwelded(open).indices);
  CHECK(w.boundaryOrNonManifoldEdges == 3);
}

TEST_CASE("mesh checker: a fin on an edge makes it non-manifold (three triangles on one edge)", "[mesh_checks]") {
  TriangleMesh fin = tetrahedron();
  fin.positions.push_back({1.0f, 1.0f, -1.0f});
  fin.indices.insert(fin.indices.end(), {0, 1, 4});
  const MeshTopology t = analyzeMesh(fin);
  CHECK(t.nonManifoldEdges == 1);
  CHECK(t.boundaryEdges == 2);  // the fin's two free edges
  CHECK_FALSE(t.manifold());
  CHECK_THAT(closedManifoldDefects(fin), Catch::Contains("1 non-manifold edges"));
  const Topology w = weldedTopology(unwelded(fin).positions, unwelded(fin).indices);
  CHECK(w.boundaryOrNonManifoldEdges == 3);
}

TEST_CASE("mesh checker: one flipped face is misoriented on its three edges, all flipped is inside out",
          "[mesh_checks]") {
  TriangleMesh flipped = tetrahedron();
  std::swap(flipped.indices[1], flipped.indices[2]);
  const MeshTopology t = analyzeMesh(flipped);
  CHECK(t.misorientedEdges == 3);
  CHECK(t.watertight());  // every edge has two triangles: only the orientation is wrong
  CHECK_FALSE(t.manifold());
  CHECK_THAT(closedManifoldDefects(flipped), Catch::Contains("3 misoriented edges"));
  const Topology w = weldedTopology(unwelded(flipped).positions, unwelded(flipped).indices);
  CHECK(w.inconsistentEdges == 3);
  CHECK(w.boundaryOrNonManifoldEdges == 0);

  // Consistently reversed: a closed manifold whose normals point inwards, which the signed volume tells.
  TriangleMesh inside = tetrahedron();
  for (size_t f = 0; f < inside.indices.size(); f += 3) std::swap(inside.indices[f + 1], inside.indices[f + 2]);
  CHECK(analyzeMesh(inside).manifold());
  CHECK(meshVolume(inside) == Approx(-1.0 / 6.0));
}

TEST_CASE("mesh checker: two tetrahedra touching at one vertex make a non-manifold vertex", "[mesh_checks]") {
  // The second tetrahedron mirrored through the origin, sharing vertex 0 only.
  TriangleMesh bow = tetrahedron();
  TriangleMesh other = tetrahedron();
  for (auto& p : other.positions) p = -p;
  for (size_t f = 0; f < other.indices.size(); f += 3) std::swap(other.indices[f + 1], other.indices[f + 2]);
  other.positions.erase(other.positions.begin());  // its vertex 0 is bow's vertex 0
  for (auto& i : other.indices) i = (i == 0) ? 0u : i + 3u;
  bow.positions.insert(bow.positions.end(), other.positions.begin(), other.positions.end());
  bow.indices.insert(bow.indices.end(), other.indices.begin(), other.indices.end());
  const MeshTopology t = analyzeMesh(bow);
  CHECK(t.watertight());  // every edge has two triangles
  CHECK(t.misorientedEdges == 0);
  CHECK(t.nonManifoldVertices == 1);
  CHECK_FALSE(t.manifold());
  CHECK_THAT(closedManifoldDefects(bow), Catch::Contains("1 non-manifold vertices"));
}

TEST_CASE("mesh checker: repeated, out-of-range and collinear indices are degenerate triangles", "[mesh_checks]") {
  TriangleMesh m = tetrahedron();
  m.positions.push_back({0.5f, 0.0f, 0.0f});  // on the edge 0-1: a zero-area triangle with them
  m.indices.insert(m.indices.end(), {0, 0, 1, 0, 1, 99, 0, 4, 1});
  const MeshTopology t = analyzeMesh(m);
  CHECK(t.degenerateTriangles == 3);
  CHECK_THAT(closedManifoldDefects(m), Catch::Contains("3 degenerate triangles"));
}

TEST_CASE("mesh checker: separate pieces are counted as components", "[mesh_checks]") {
  const TriangleMesh two = joined(tetrahedron(), tetrahedron({3.0f, 0.0f, 0.0f}));
  const MeshTopology t = analyzeMesh(two);
  CHECK(t.components == 2);
  CHECK(t.manifold());
  CHECK(t.genus() == 0);
  const Topology w = weldedTopology(unwelded(two).positions, unwelded(two).indices);
  CHECK(w.components == 2);
  CHECK(w.vertices == 8);
  CHECK(w.eulerCharacteristic() == 4);
}
