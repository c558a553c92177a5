// A map subtree made of one affine map over one point primitive (a meta-primitive's instance) is
// evaluated in one loop, with or without gradients: its values and gradients must be those of
// the ops run one by one (the map's transform, the point's potential, the gradient mapped back by
// the transposed matrix), bit for bit.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "core/field/field_program.h"
#include "core/field/potential.h"
#include "core/field/space_map.h"

using namespace animorph;

TEST_CASE("an affine map over a point primitive gives the ops' values and gradients bit for bit", "[field_program]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.5f, 1.5f);
  int within = 0, compared = 0;
  for (int c = 0; c < 16; ++c) {
    const glm::quat rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng) + 1.5f));
    const SpaceMap m = makeAffineMap(glm::vec3(u(rng), u(rng), u(rng)) * 0.3f, rotation,
                                     glm::vec3(pos(rng), pos(rng), pos(rng)) * 0.4f);
    SkeletalPrimitive p;
    p.skeleton.kind = SkeletonKind::Point;
    p.skeleton.p0 = glm::vec3(u(rng), u(rng), u(rng)) * 0.2f;
    p.radius = 0.4f + 0.3f * pos(rng);
    p.intensity = 0.5f + 0.5f * pos(rng);
    p.stiffness = float(1 + c % 4);
    const bool union_ = c % 2 == 1;
    FieldProgram prog;
    prog.threshold = 0.3f;
    prog.beginMap(m);
    prog.addSkeletal(p, false, union_);
    prog.endMap();
    prog.finish();
    ActiveProgram all;
    prog.specialiseAll(all);
    REQUIRE(all.ops.size() == 3);
    std::vector<float> x, y, z;
    for (int i = 0; i < 64; ++i) {
      x.push_back(u(rng) * 0.25f);
      y.push_back(u(rng) * 0.25f);
      z.push_back(u(rng) * 0.25f);
    }
    const size_t n = x.size();
    std::vector<float> f(n), v(n), gx(n), gy(n), gz(n);
    FieldEvaluator ev;
    ev.evaluate(prog, all, x.data(), y.data(), z.data(), int(n), f.data(), gx.data(), gy.data(), gz.data());
    ev.evaluate(prog, all, x.data(), y.data(), z.data(), int(n), v.data());
    for (size_t i = 0; i < n; ++i) {
      // The ops one by one: BeginMap, the skeletal kernel (from zeros), EndMap.
      const glm::vec3 q = m.toLocal(glm::vec3(x[i], y[i], z[i]));
      const glm::vec3 d = q - p.skeleton.p0;
      const float d2 = glm::dot(d, d);
      float gf;
      const float pot = skeletalPotential(d2, p.radius, p.intensity, p.stiffness, gf);
      float want = 0.0f;
      glm::vec3 local(0.0f);
      if (d2 < p.radius * p.radius && (!union_ || pot > 0.0f)) {
        want = union_ ? pot : 0.0f + pot;
        local = union_ ? gf * d : glm::vec3(0.0f) + gf * d;
      }
      const glm::vec3 world = glm::transpose(m.linear) * local;
      INFO("case " << c << " point " << i);
      CHECK(f[i] == want - prog.threshold);
      CHECK(v[i] == want - prog.threshold);
      CHECK(gx[i] == world.x);
      CHECK(gy[i] == world.y);
      CHECK(gz[i] == world.z);
      within += want > 0.0f;
      ++compared;
    }
  }
  CHECK(within > compared / 8);
  CHECK(within < compared);
}
