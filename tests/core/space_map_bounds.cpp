#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/field/field_program.h"
#include "core/field/space_map.h"

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

namespace {

// A primitive's world bound by its definition (field_program.h): its capsule (a, b, radius) and box
// carried out through the maps, innermost first; under a uniformly scaled rigid map (scale s) the
// capsule maps to a capsule and the box is the map's world box cut by the capsule's box, under any
// other map the box alone is carried and the capsule becomes its bounding sphere.
PrimitiveBound boundThroughMaps(glm::vec3 a, glm::vec3 b, float radius, const std::vector<SpaceMap>& maps,
                                const std::vector<float>& rigidScale) {
  auto capsuleBox = [](const glm::vec3& p, const glm::vec3& q, float r) {
    Bounds box;
    box.add(glm::min(p, q) - glm::vec3(r));
    box.add(glm::max(p, q) + glm::vec3(r));
    return box;
  };
  PrimitiveBound pb{a, b, radius, capsuleBox(a, b, radius)};
  for (size_t level = maps.size(); level-- > 0;) {
    const Bounds box = maps[level].worldBounds(pb.box);
    if (rigidScale[level] < 0.0f) {
      pb.box = box;
      pb.a = pb.b = box.center();
      pb.radius = 0.5f * box.diagonal();
      continue;
    }
    pb.a = maps[level].toWorld(pb.a);
    pb.b = maps[level].toWorld(pb.b);
    pb.radius *= rigidScale[level];
    const Bounds cap = capsuleBox(pb.a, pb.b, pb.radius);
    Bounds both;
    if (!box.empty()) {
      both.min = glm::max(box.min, cap.min);
      both.max = glm::min(box.max, cap.max);
    }
    const bool empty = box.empty() || both.min.x > both.max.x || both.min.y > both.max.y || both.min.z > both.max.z;
    pb.box = empty ? cap : both;
  }
  return pb;
}

std::vector<SkeletalPrimitive> randomTriangles(std::mt19937& rng, std::uniform_real_distribution<float>& d, size_t n,
                                               float radius) {
  std::vector<SkeletalPrimitive> tris(n);
  for (SkeletalPrimitive& t : tris) {
    t.skeleton.kind = SkeletonKind::Triangle;
    t.skeleton.p0 = glm::vec3(d(rng), d(rng), d(rng));
    t.skeleton.p1 = glm::vec3(d(rng), d(rng), d(rng));
    t.skeleton.p2 = glm::vec3(d(rng), d(rng), d(rng));
    t.radius = radius;
  }
  return tris;
}

bool sameBound(const PrimitiveBound& x, const PrimitiveBound& y) {
  return sameBits(x.a, y.a) && sameBits(x.b, y.b) && std::memcmp(&x.radius, &y.radius, sizeof x.radius) == 0 &&
         sameBits(x.box.min, y.box.min) && sameBits(x.box.max, y.box.max);
}

}  // namespace

TEST_CASE("field programs: primitive bounds through nested maps equal the maps' own operations bit for bit",
          "[field]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> d(-2.0f, 2.0f);
  std::uniform_real_distribution<float> sc(0.3f, 2.5f);
  int checked = 0, mismatches = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // 1-6 nested maps: rigid with a uniform scale (the vector path), axis-aligned at the origin
    // (zero bounds: the scalar path decides), non-uniform scales and a twist (the scalar path).
    const int depth = 1 + trial % 6;
    std::vector<SpaceMap> maps;
    std::vector<float> rigid;
    FieldProgram prog;
    for (int k = 0; k < depth; ++k) {
      const int kind = (trial + 3 * k) % 7;
      SpaceMap m;
      if (kind == 5) m = makeAffineMap(glm::vec3(d(rng), d(rng), d(rng)), glm::quat(1, 0, 0, 0),
                                       glm::vec3(sc(rng), sc(rng), sc(rng)));
      else if (kind == 6 && trial % 2 == 0) m = makeTwistMap(glm::vec3(0.0f), glm::vec3(0, 1, 0), d(rng));
      else if (kind == 4) m = makeAffineMap(glm::vec3(0.0f), glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0)),
                                            glm::vec3(sc(rng)));
      else m = makeAffineMap(glm::vec3(d(rng), d(rng), d(rng)),
                             glm::normalize(glm::quat(d(rng), d(rng), d(rng), d(rng))), glm::vec3(sc(rng)));
      const glm::mat3& f = m.forwardLinear;
      const float s0 = glm::length(f[0]), tol = 1e-4f * s0;
      const bool uniform = m.kind == SpaceMapKind::Affine && std::abs(s0 - glm::length(f[1])) <= tol &&
                           std::abs(s0 - glm::length(f[2])) <= tol && std::abs(glm::dot(f[0], f[1])) <= tol * s0 &&
                           std::abs(glm::dot(f[0], f[2])) <= tol * s0 && std::abs(glm::dot(f[1], f[2])) <= tol * s0;
      maps.push_back(m);
      rigid.push_back(uniform ? s0 : -1.0f);
      prog.beginMap(m);
    }
    // Points (a and b the same), segments, and a run of three triangles (bounds computed in pairs).
    SkeletalPrimitive point;
    point.skeleton.kind = SkeletonKind::Point;
    point.skeleton.p0 = trial % 4 == 0 ? glm::vec3(0.0f) : glm::vec3(d(rng), d(rng), d(rng));
    point.radius = sc(rng);
    prog.addSkeletal(point, false, false);
    SkeletalPrimitive segment;
    segment.skeleton.kind = SkeletonKind::Segment;
    segment.skeleton.p0 = glm::vec3(d(rng), d(rng), d(rng));
    segment.skeleton.p1 = glm::vec3(d(rng), d(rng), d(rng));
    segment.radius = sc(rng);
    prog.addSkeletal(segment, true, false);
    const std::vector<SkeletalPrimitive> tris = randomTriangles(rng, d, 3, 0.1f);
    prog.addSkeletalRun(tris.data(), tris.size(), false, true);
    for (int k = 0; k < depth; ++k) prog.endMap();
    REQUIRE(prog.skeletalReach.size() == prog.primitiveBounds.size());
    for (size_t i = 0; i < prog.primitiveBounds.size(); ++i) {
      const SkeletalReach& r = prog.skeletalReach[i];
      ++checked;
      mismatches += sameBound(prog.primitiveBounds[i], boundThroughMaps(r.a, r.b, r.reach, maps, rigid)) ? 0 : 1;
    }
  }
  CHECK(checked == 300 * 5);
  CHECK(mismatches == 0);
}

TEST_CASE("field programs: a run of skeletal primitives is the same program as adding them one by one", "[field]") {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> d(-1.0f, 1.0f);
  const std::vector<SkeletalPrimitive> tris = randomTriangles(rng, d, 7, 0.2f);
  auto build = [&](bool run) {
    FieldProgram p;
    p.beginMap(makeAffineMap(glm::vec3(0.5f, 0, 0), glm::angleAxis(0.3f, glm::vec3(0, 0, 1)), glm::vec3(1.5f)));
    p.beginMap(makeAffineMap(glm::vec3(0, -0.2f, 0.1f), glm::angleAxis(1.1f, glm::vec3(1, 0, 0)), glm::vec3(0.7f)));
    SkeletalPrimitive first = tris[0];
    first.skeleton.kind = SkeletonKind::Point;
    p.addSkeletal(first, false, true);
    bool pushed = false;
    if (run) {
      pushed = p.addSkeletalRun(tris.data(), tris.size(), true, true);
    } else {
      for (size_t i = 0; i < tris.size(); ++i) {
        const bool added = p.addSkeletal(tris[i], true, true);
        if (i == 0) pushed = added;
      }
    }
    CHECK_FALSE(pushed);  // joined the point's union op
    CHECK_FALSE(p.addSkeletalRun(tris.data(), 0, false, true));
    p.endMap();
    p.endMap();
    p.finish();
    return p;
  };
  const FieldProgram one = build(false), run = build(true);
  REQUIRE(one.ops.size() == run.ops.size());
  REQUIRE(one.primitiveBounds.size() == tris.size() + 1);
  REQUIRE(run.primitiveBounds.size() == one.primitiveBounds.size());
  for (size_t i = 0; i < one.ops.size(); ++i) {
    CHECK(one.ops[i].code == run.ops[i].code);
    CHECK(one.ops[i].count == run.ops[i].count);
    CHECK(one.ops[i].first == run.ops[i].first);
  }
  for (size_t i = 0; i < one.primitiveBounds.size(); ++i) CHECK(sameBound(one.primitiveBounds[i], run.primitiveBounds[i]));
  CHECK(std::memcmp(one.skeletalReach.data(), run.skeletalReach.data(), sizeof(SkeletalReach) * one.skeletalReach.size()) == 0);
}
