#include <catch2/catch.hpp>

#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/generic_tree.h"
#include "core/blobtree/compile.h"
#include "core/poly/polygonizer.h"
#include "util/animorph_fixtures.h"
#include "util/mesh_checks.h"

using namespace animorph;
using namespace animorph::test;

namespace {

Topology topologyOf(const FieldProgram& program, int resolution) {
  PolygonizeSettings s;
  s.resolution = resolution;
  auto r = polygonize(program, s);
  REQUIRE(r.ok());
  REQUIRE(r->mesh.triangleCount() > 100);
  return weldedTopology(r->mesh.positions, r->mesh.indices);
}

}  // namespace

TEST_CASE("animorphosis: every frame of the walker -> flyer is watertight and consistently oriented, the ends have "
          "the topology of A and B",
          "[animorph]") {
  auto c = buildGenericTree(walkerTree(), flyerTree(), walkerToFlyerGraph());
  REQUIRE(c.ok());
  AnimorphosisTiming timing;
  timing.startSec = 1.0;
  timing.endSec = 3.0;
  timing.target = {0.5, 1.0, 0.5};
  const int res = 48;
  size_t frames = 0;
  for (double t = 0.8; t <= 3.2 + 1e-9; t += 0.2) {
    Topology top = topologyOf(compileGeneric(*c, timing, t), res);
    INFO("t = " << t << ": " << top.components << " components, genus " << top.genus() << ", "
                << top.boundaryOrNonManifoldEdges << " open or non-manifold edges");
    CHECK(top.boundaryOrNonManifoldEdges == 0);
    CHECK(top.inconsistentEdges == 0);
    ++frames;
  }
  CHECK(frames == 13);
  Topology first = topologyOf(compileGeneric(*c, timing, 0.8), res);
  Topology a = topologyOf(compileFieldProgram(walkerTree(), timing.source.localTime(0.8)), res);
  CHECK(first.components == a.components);
  CHECK(first.genus() == a.genus());
  Topology last = topologyOf(compileGeneric(*c, timing, 3.2), res);
  Topology b = topologyOf(compileFieldProgram(flyerTree(), timing.target.localTime(3.2)), res);
  CHECK(last.components == b.components);
  CHECK(last.genus() == b.genus());
}
