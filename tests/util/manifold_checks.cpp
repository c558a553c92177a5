#include "util/manifold_checks.h"

#include <catch2/catch.hpp>

#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"

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

double polygonisedVolume(const FieldProgram& program, const Bounds& box, int resolution) {
  PolygonizeSettings ps;
  ps.resolution = resolution;
  ps.bounds = box;
  auto r = polygonize(program, ps);
  REQUIRE(r);
  REQUIRE(analyzeMesh(r->mesh).watertight());
  return meshVolume(r->mesh);
}

}  // namespace animorph::test
