#include <catch2/catch.hpp>

#include <cstring>
#include <random>

#include "field/space_map.h"

using namespace animorph;

namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// An affine map's world box by its definition: the box of toWorld's 8 corners, computed with glm.
Bounds cornerBox(const SpaceMap& m, const Bounds& child) {
  Bounds out;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c{i & 1 ? child.max.x : child.min.x, i & 2 ? child.max.y : child.min.y,
                i & 4 ? child.max.z : child.min.z};
    out.add(m.origin + m.forwardLinear * c);
  }
  return out;
}

}  // namespace

TEST_CASE("space maps: affine world boxes and toWorld equal the corner images bit for bit", "[field]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> d(-4.0f, 4.0f);
  std::uniform_real_distribution<float> sc(0.2f, 3.0f);
  int boxMismatches = 0, pointMismatches = 0;
  for (int i = 0; i < 3000; ++i) {
    // Random frames, and axis-aligned ones (zero matrix entries, zero origins: signed zeros).
    const bool aligned = i % 3 == 0;
    glm::quat q = aligned ? glm::angleAxis(glm::radians(90.0f * float(i % 4)), glm::vec3(0, 0, 1))
                          : glm::normalize(glm::quat(d(rng), d(rng), d(rng), d(rng)));
    glm::vec3 t = aligned && i % 2 == 0 ? glm::vec3(0.0f) : glm::vec3(d(rng), d(rng), d(rng));
    glm::vec3 s = i % 5 == 0 ? glm::vec3(sc(rng)) : glm::vec3(sc(rng), -sc(rng), sc(rng));
    SpaceMap m = makeAffineMap(t, q, s);
    Bounds child;
    glm::vec3 a(d(rng), d(rng), d(rng)), b(d(rng), d(rng), d(rng));
    if (i % 7 == 0) a = glm::vec3(0.0f);  // a corner at the origin
    child.add(a);
    child.add(b);
    const Bounds got = m.worldBounds(child), want = cornerBox(m, child);
    boxMismatches += sameBits(got.min, want.min) && sameBits(got.max, want.max) ? 0 : 1;
    pointMismatches += sameBits(m.toWorld(a), m.origin + m.forwardLinear * a) ? 0 : 1;
  }
  CHECK(boxMismatches == 0);
  CHECK(pointMismatches == 0);
}
