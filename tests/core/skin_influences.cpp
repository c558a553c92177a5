#include <catch2/catch.hpp>

#include <cmath>

#include "core/rig/skin_influences.h"

using namespace animorph;

TEST_CASE("influence packing keeps the largest, merges duplicates and normalises", "[rig]") {
  glm::uvec4 j0, j1;
  glm::vec4 w0, w1;
  InfluenceStats stats;
  std::vector<Influence> in = {{3, 0.1f}, {1, 0.4f}, {3, 0.1f}, {7, 0.2f}, {2, -1.0f}, {5, NAN}};
  packInfluences(in, j0, w0, j1, w1, stats);
  CHECK(j0 == glm::uvec4(1, 3, 7, 0));
  CHECK(w0.x == Approx(0.5f));
  CHECK(w0.y == Approx(0.25f));
  CHECK(w0.z == Approx(0.25f));
  CHECK(w0.w == 0.0f);
  CHECK(stats.normalised == 1);
  CHECK(stats.dropped == 0);
  // Exactly normalised input is not counted.
  in = {{0, 0.5f}, {1, 0.5f}};
  packInfluences(in, j0, w0, j1, w1, stats);
  CHECK(stats.normalised == 1);
  // Ten influences: the two smallest are dropped, the rest fill both sets.
  in.clear();
  for (uint32_t j = 0; j < 10; ++j) in.push_back({j, 0.01f * (j + 1)});
  packInfluences(in, j0, w0, j1, w1, stats);
  CHECK(stats.dropped == 1);
  CHECK(j0 == glm::uvec4(9, 8, 7, 6));
  CHECK(j1 == glm::uvec4(5, 4, 3, 2));
  CHECK(w0.x + w0.y + w0.z + w0.w + w1.x + w1.y + w1.z + w1.w == Approx(1.0f));
  in.clear();
  packInfluences(in, j0, w0, j1, w1, stats);
  CHECK(stats.unweighted == 1);
  CHECK(w0 == glm::vec4(1, 0, 0, 0));
}
