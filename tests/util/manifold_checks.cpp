#include "util/manifold_checks.h"

#include <catch2/catch.hpp>

#include "poly/mesh_checks.h"

namespace animorph::test {

void requireClosedManifold(const TriangleMesh& m) {
  MeshTopology t = analyzeMesh(m);
  CHECK(t.boundaryEdges == 0);
  CHECK(t.nonManifoldEdges == 0);
  CHECK(t.misorientedEdges == 0);
  CHECK(t.nonManifoldVertices == 0);
  CHECK(t.degenerateTriangles == 0);
  CHECK(t.manifold());
}

}  // namespace animorph::test
