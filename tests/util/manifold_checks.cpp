#include "util/manifold_checks.h"

#include <catch2/catch.hpp>

#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"

namespace animorph::test {

std::string closedManifoldDefects(const TriangleMesh& m) {
  const MeshTopology t = analyzeMesh(m);
  std::string out;
  auto note = [&out](size_t n, const char* what) {
    if (n == 0) return;
    if (!out.empty()) out += ", ";
    out += std::to_string(n) + " " + what;
  };
  note(t.boundaryEdges, "boundary edges");
  note(t.nonManifoldEdges, "non-manifold edges");
  note(t.misorientedEdges, "misoriented edges");
  note(t.nonManifoldVertices, "non-manifold vertices");
  note(t.degenerateTriangles, "degenerate triangles");
  if (out.empty() && !t.manifold()) out = "not a closed manifold";  // a kind analyzeMesh adds later
  return out;
}

void requireClosedManifold(const TriangleMesh& m) {
  const std::string defects = closedManifoldDefects(m);
  INFO("mesh of " << m.triangleCount() << " triangles: " << defects);
  CHECK(defects.empty());
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
