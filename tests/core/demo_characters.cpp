#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "demo/creature.h"
#include "demo/dense.h"
#include "demo/gear.h"
#include "core/rig/pose.h"
#include "core/rig/skinning.h"
#include "util/mesh_checks.h"

using namespace animorph;

namespace {

void checkWeights(const Mesh& m, size_t jointCount) {
  REQUIRE(m.weights0.size() == m.vertexCount());
  for (size_t v = 0; v < m.vertexCount(); ++v) {
    const glm::vec4 w = m.weights0[v];
    CHECK(w.x + w.y + w.z + w.w == Approx(1.0f).margin(1e-5));
    for (int k = 0; k < 4; ++k) CHECK(m.joints0[v][k] < jointCount);
  }
}

void checkLoops(const Character& c) {
  const auto& clip = c.clips[0];
  auto a = skinnedWorldPositions(c, &clip, 0.0f), b = skinnedWorldPositions(c, &clip, clip.durationSec);
  float worst = 0.0f;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
  CHECK(worst < 1e-4f);
}

}  // namespace

TEST_CASE("creature: closed genus-0 skinned surface with a looping walk", "[demo]") {
  const Character c = makeCreatureCharacter();
  REQUIRE(c.meshes.size() == 1);
  const Mesh& m = c.meshes[0];
  CHECK(m.triangleCount() >= 2000);
  CHECK(m.triangleCount() <= 10000);
  const auto topo = test::weldedTopology(m.positions, m.indices);
  CHECK(topo.boundaryOrNonManifoldEdges == 0);
  CHECK(topo.inconsistentEdges == 0);
  CHECK(topo.components == 1);
  CHECK(topo.eulerCharacteristic() == 2);
  CHECK(c.totalJoints() >= 10);
  checkWeights(m, c.skins[0].joints.size());
  // Smooth weights: a good share of vertices blend two or more bones.
  size_t blended = 0;
  for (const auto& w : m.weights0) blended += w.y > 0.2f;
  CHECK(blended > m.vertexCount() / 10);
  // Normals point outwards: the signed volume is positive.
  double volume = 0.0;
  for (size_t t = 0; t < m.indices.size(); t += 3)
    volume += glm::dot(m.positions[m.indices[t]], glm::cross(m.positions[m.indices[t + 1]], m.positions[m.indices[t + 2]])) / 6.0;
  CHECK(volume > 0.01);
  REQUIRE(c.clips.size() == 1);
  CHECK(c.clips[0].name == "walk");
  CHECK(c.clips[0].durationSec == Approx(2.0f));
  checkLoops(c);
  // Feet touch the ground; the walk really moves them.
  CHECK(m.bounds().min.y == Approx(0.0f).margin(0.02));
  auto rest = skinnedWorldPositions(c, &c.clips[0], 0.0f), mid = skinnedWorldPositions(c, &c.clips[0], 0.5f);
  float moved = 0.0f;
  for (size_t i = 0; i < rest.size(); ++i) moved = std::max(moved, glm::length(rest[i] - mid[i]));
  CHECK(moved > 0.05f);
  // Deterministic.
  const Character again = makeCreatureCharacter();
  CHECK(again.meshes[0].positions == m.positions);
  CHECK(again.meshes[0].weights0 == m.weights0);
}

TEST_CASE("gear: teeth and holes (genus >= 3), two bones, a full turn", "[demo]") {
  const Character c = makeGearCharacter();
  const Mesh& m = c.meshes[0];
  const auto topo = test::weldedTopology(m.positions, m.indices);
  CHECK(topo.boundaryOrNonManifoldEdges == 0);
  CHECK(topo.inconsistentEdges == 0);
  CHECK(topo.components == 1);
  CHECK(topo.genus() == 5);
  CHECK(c.totalJoints() == 2);
  checkWeights(m, 2);
  const auto& clip = c.clips[0];
  CHECK(clip.name == "turn");
  checkLoops(c);
  // At t = 1 s the hub has turned a quarter (clockwise seen from +Z) about
  // its centre: hub-only vertices follow exactly.
  const glm::vec3 centre(0, 0.36f, 0);
  const glm::mat4 quarter = glm::translate(glm::mat4(1.0f), centre) *
                            glm::rotate(glm::mat4(1.0f), -glm::half_pi<float>(), glm::vec3(0, 0, 1)) *
                            glm::translate(glm::mat4(1.0f), -centre);
  auto p = skinnedWorldPositions(c, &clip, 1.0f);
  size_t hubOnly = 0;
  for (size_t v = 0; v < m.vertexCount(); ++v)
    if (m.joints0[v].x == 0 && m.weights0[v].x == 1.0f) {
      ++hubOnly;
      CHECK(glm::length(p[v] - glm::vec3(quarter * glm::vec4(m.positions[v], 1))) < 1e-4f);
    }
  CHECK(hubOnly > 100);
}

TEST_CASE("dense character hits its triangle target", "[demo]") {
  const Character c = makeDenseCharacter(100000);
  CHECK(c.totalTriangles() >= 95000);
  CHECK(c.totalTriangles() <= 105000);
  const auto topo = test::weldedTopology(c.meshes[0].positions, c.meshes[0].indices);
  CHECK(topo.boundaryOrNonManifoldEdges == 0);
  CHECK(topo.eulerCharacteristic() == 2);
  checkWeights(c.meshes[0], c.skins[0].joints.size());
}
