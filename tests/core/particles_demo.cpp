#include <catch2/catch.hpp>

#include <cmath>
#include <unordered_map>

#include "core/animorphosis/evaluate_generic.h"
#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "demo/statue.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"

using namespace animorph;

namespace {

const std::string kStatueProject = std::string(ANIMORPH_SOURCE_DIR) + "/resources/demo/statue.animorph";

// Largest distance from a vertex of a to the nearest vertex of b, searched up to `cap`
// (returns cap when some vertex has no neighbour that close).
float directedDistance(const TriangleMesh& a, const TriangleMesh& b, float cap) {
  auto key = [&](const glm::vec3& p) {
    glm::ivec3 c = glm::ivec3(glm::floor(p / cap));
    return (int64_t(c.x) * 73856093) ^ (int64_t(c.y) * 19349663) ^ (int64_t(c.z) * 83492791);
  };
  std::unordered_multimap<int64_t, uint32_t> grid;
  for (uint32_t i = 0; i < b.positions.size(); ++i) grid.emplace(key(b.positions[i]), i);
  float worst = 0.0f;
  for (const glm::vec3& p : a.positions) {
    float best = cap;
    glm::ivec3 c = glm::ivec3(glm::floor(p / cap));
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          glm::vec3 q = (glm::vec3(c + glm::ivec3(dx, dy, dz)) + 0.5f) * cap;
          auto range = grid.equal_range(key(q));
          for (auto it = range.first; it != range.second; ++it)
            best = std::min(best, glm::length(b.positions[it->second] - p));
        }
    worst = std::max(worst, best);
  }
  return worst;
}

float hausdorff(const TriangleMesh& a, const TriangleMesh& b, float cap) {
  return std::max(directedDistance(a, b, cap), directedDistance(b, a, cap));
}

TriangleMesh meshOf(const FieldProgram& program, const Bounds& box) {
  PolygonizeSettings ps;
  ps.resolution = 128;
  ps.bounds = box;
  auto r = polygonize(program, ps);
  REQUIRE(r);
  return r->mesh;
}

}  // namespace

TEST_CASE("statue demo: first and last frames match the statue, it scatters in between", "[particles][demo]") {
  auto demo = makeStatueDemo();
  REQUIRE(demo);
  const Project& p = demo->project;
  auto c = projectGenericTree(p);
  REQUIRE(c);
  AnimorphosisTiming timing = animorphosisTiming(p);
  FieldProgram statue = compileFieldProgram(makeStatue(), 0.0);
  Bounds box = statue.tightBounds();
  box.min -= glm::vec3(0.1f);
  box.max += glm::vec3(0.1f);
  float cell = std::max({box.size().x, box.size().y, box.size().z}) / 128.0f;
  TriangleMesh reference = meshOf(statue, box);
  double first = p.timeline.frameToSec(p.timeline.frameStart), last = p.timeline.frameToSec(p.timeline.frameEnd);
  REQUIRE(first < p.animorphosis.startSec);
  REQUIRE(last > p.animorphosis.endSec);
  TriangleMesh a = meshOf(compileGeneric(*c, timing, first), box);
  TriangleMesh b = meshOf(compileGeneric(*c, timing, last), box);
  float ha = hausdorff(reference, a, 4.0f * cell), hb = hausdorff(reference, b, 4.0f * cell);
  INFO("Hausdorff to the statue: first frame " << ha / cell << " cells, last " << hb / cell << " cells; "
       << demo->animorphosis.explosionReport.particles << " particles");
  CHECK(ha <= 2.0f * cell);
  CHECK(hb <= 2.0f * cell);
  CHECK(hausdorff(a, b, 4.0f * cell) <= 0.1f * cell);  // the same particles at rest
  // Mid-way the particles are spread far beyond the statue.
  FieldProgram mid = compileGeneric(*c, timing, 0.5 * (p.animorphosis.startSec + p.animorphosis.endSec));
  Bounds spread = mid.bounds();
  CHECK(spread.size().x > 2.0f * statue.tightBounds().size().x);
}

TEST_CASE("statue demo: the committed project is what make-statue-demo writes", "[particles][demo]") {
  auto committed = loadProject(kStatueProject);
  REQUIRE(committed);
  REQUIRE(checkAnimorphosis(*committed));
  auto made = makeStatueDemo();
  REQUIRE(made);
  REQUIRE(committed->actors.size() == 2);
  CHECK(blobTreeToJson(committed->actors[0].blobTree) == blobTreeToJson(made->project.actors[0].blobTree));
  CHECK(blobTreeToJson(committed->actors[1].blobTree) == blobTreeToJson(made->project.actors[1].blobTree));
  CHECK(committed->animorphosis.graph == made->project.animorphosis.graph);
  CHECK(committed->animorphosis.endSec == made->project.animorphosis.endSec);
}
