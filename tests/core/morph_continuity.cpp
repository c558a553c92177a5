// No pops: the bounded interpolation's remnant of the source is gone by
// w = 1 - 1/K (the unbounded sum keeps one near the skeleton until w = 1) and
// shrinks monotonically on the way; the bake's continuity report flags empty
// frames and volume jumps, and only those.
#include <catch2/catch.hpp>

#include <limits>
#include <random>

#include "core/field/skeleton.h"
#include "core/standin_morph/mesh_distance.h"
#include "core/standin_morph/morph_continuity.h"
#include "core/standin_morph/morph_field.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

// Two stand-ins far apart: whatever is inside near the source's skeleton is the source's remnant.
MorphOperand side(glm::vec3 a, glm::vec3 b, float radius) {
  MorphOperand o;
  o.kind = StandinKind::Convolution;
  o.sharpness = 2.5f / radius;
  o.segments = {{a, b, radius, 1.0f}};
  return o;
}

double remnantVolume(const MorphOperand& src, const MorphOperand& dst, float w, float bound) {
  const FieldProgram p = buildMorphProgram(src, dst, MorphMethod::Interpolation, w, {}, bound);
  PolygonizeSettings ps;
  ps.resolution = 48;
  Bounds box;
  box.add(glm::vec3(-0.4f, -0.3f, -0.3f));
  box.add(glm::vec3(1.4f, 0.3f, 0.3f));
  ps.bounds = box;
  auto r = polygonize(p, ps);
  REQUIRE(r.ok());
  return r->mesh.triangleCount() ? meshVolume(r->mesh) : 0.0;
}

}  // namespace

TEST_CASE("bounded interpolation: the source's remnant shrinks to nothing by w = 1 - 1/K", "[morph][continuity]") {
  const MorphOperand src = side({0, 0, 0}, {1, 0, 0}, 0.1f);
  const MorphOperand dst = side({0, 3, 0}, {1, 3, 0}, 0.1f);  // out of the box: the box holds the source only
  const float K = 4.0f;
  const glm::vec3 onSkeleton(0.5f, 0.0f, 0.0f);
  for (float w : {0.0f, 1.0f}) {  // the ends are the stand-ins, bounded or not
    const FieldProgram b = buildMorphProgram(src, dst, MorphMethod::Interpolation, w, {}, K);
    const FieldProgram u = buildMorphProgram(src, dst, MorphMethod::Interpolation, w, {}, 0.0f);
    for (glm::vec3 x : {onSkeleton, glm::vec3(0.5f, 0.09f, 0.0f), glm::vec3(0.5f, 0.11f, 0.0f), glm::vec3(0.5f, 3.0f, 0.0f)})
      CHECK(test::fieldAt(b, x) == Approx(test::fieldAt(u, x)).margin(1e-6));
  }
  // Unbounded: a remnant sits on the skeleton until late (its peak potential is many T).
  CHECK(test::fieldAt(buildMorphProgram(src, dst, MorphMethod::Interpolation, 0.9f, {}, 0.0f), onSkeleton) > 0.0f);
  // Bounded: nothing left of the source from w = 1 - 1/K on.
  for (float w : {1.0f - 1.0f / K + 1e-3f, 0.9f, 0.99f})
    CHECK(test::fieldAt(buildMorphProgram(src, dst, MorphMethod::Interpolation, w, {}, K), onSkeleton) < 0.0f);
  // On the way its volume falls monotonically, without a step: no frame of w in 1/32 steps loses
  // more than a third of the stand-in's volume at once.
  const double full = remnantVolume(src, dst, 0.0f, K);
  REQUIRE(full > 0.0);
  double prev = full;
  for (int k = 1; k <= 32; ++k) {
    const float w = float(k) / 32.0f;
    const double v = remnantVolume(src, dst, w, K);
    INFO("w = " << w << ": " << v / full << " of the stand-in");
    CHECK(v <= prev + 1e-3 * full);
    CHECK(prev - v <= full / 3.0);
    prev = v;
  }
  CHECK(prev == 0.0);
}

TEST_CASE("continuity report: empty frames and volume jumps over the stated fraction, nothing else",
          "[morph][continuity]") {
  std::vector<FrameMeasure> f = {{10, 100, 1.00}, {11, 100, 1.05}, {12, 100, 0.70}, {13, 0, 0.0},
                                 {14, 100, 0.70}, {15, 100, 0.81}, {16, 100, 0.90}};
  const auto d = continuityDefects(f, 0.2);
  REQUIRE(d.size() == 2);
  CHECK(d[0].frame == 12);
  CHECK(d[0].reason == "volume -33% from frame 11");
  CHECK(d[1].frame == 13);
  CHECK(d[1].reason == "empty");
  CHECK(continuityDefects(f, 0.5).size() == 1);
  CHECK(relativeVolumeChange(1.0, 0.5) == Approx(0.5));
  CHECK(relativeVolumeChange(0.0, 0.0) == 0.0);
}

TEST_CASE("Hausdorff distance between frames: symmetric, zero on itself, the offset of a moved copy",
          "[morph][continuity]") {
  auto cube = [](glm::vec3 o) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) m.positions.push_back(o + glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
  };
  const TriangleMesh a = cube(glm::vec3(0.0f)), b = cube(glm::vec3(0.0f, 0.0f, 0.25f));
  CHECK(hausdorffDistance(a, a) == Approx(0.0).margin(1e-7));
  CHECK(hausdorffDistance(a, b) == Approx(0.25).margin(1e-6));
  CHECK(hausdorffDistance(b, a) == Approx(0.25).margin(1e-6));
  CHECK(std::isinf(hausdorffDistance(a, TriangleMesh{})));
}

TEST_CASE("point-to-mesh distances: the grid search and the largest distance equal a search of every triangle",
          "[morph][continuity]") {
  // Seeded triangle soups: a dense cluster and long slivers across the box (listed in many cells),
  // points inside, near and far outside the box, and the vertices of a jittered copy (consecutive
  // frames, where the largest distance stops early at almost every point).
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto v3 = [&](float s) { return glm::vec3(u(rng), u(rng), u(rng)) * s; };
    TriangleMesh mesh;
    const int nt = 200 + int(seed) * 150;
    for (int t = 0; t < nt; ++t) {
      const glm::vec3 c = t % 7 == 0 ? v3(1.0f) : v3(0.3f) + glm::vec3(0.5f, 0.0f, 0.0f);
      const float size = t % 11 == 0 ? 1.5f : 0.05f;
      for (int k = 0; k < 3; ++k) {
        mesh.indices.push_back(uint32_t(mesh.positions.size()));
        mesh.positions.push_back(c + v3(size));
      }
    }
    std::vector<glm::vec3> points;
    for (int i = 0; i < 300; ++i) points.push_back(v3(i % 5 == 0 ? 4.0f : 1.2f));
    for (const glm::vec3& p : mesh.positions) points.push_back(p + v3(0.01f));
    auto brute = [&](const glm::vec3& p) {
      float best = std::numeric_limits<float>::infinity();
      for (size_t t = 0; t < mesh.triangleCount(); ++t)
        best = std::min(best, glm::length(p - closestOnTriangle(p, mesh.positions[mesh.indices[3 * t]],
                                                                   mesh.positions[mesh.indices[3 * t + 1]],
                                                                   mesh.positions[mesh.indices[3 * t + 2]])));
      return best;
    };
    const std::vector<float> grid = pointDistancesToMesh(points, mesh);
    float largest = 0.0f;
    for (size_t i = 0; i < points.size(); ++i) {
      const float b = brute(points[i]);
      largest = std::max(largest, b);
      REQUIRE(grid[i] == Approx(b).margin(1e-6));
    }
    CHECK(maxPointToMeshDistance(points, mesh) == Approx(largest).margin(1e-6));
    const std::vector<glm::vec3> near(points.begin() + 300, points.end());
    float nearLargest = 0.0f;
    for (const glm::vec3& p : near) nearLargest = std::max(nearLargest, brute(p));
    CHECK(maxPointToMeshDistance(near, mesh) == Approx(nearLargest).margin(1e-6));
  }
  CHECK(maxPointToMeshDistance({}, TriangleMesh{}) == 0.0);
  CHECK(std::isinf(maxPointToMeshDistance({glm::vec3(0.0f)}, TriangleMesh{})));
}
