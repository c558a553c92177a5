// A union (max) of triangle primitives that share radius, intensity and stiffness (a Coons patch's
// triangles) is evaluated nearest-first with pruning, and its interval from the nearest triangle
// alone: values, gradients and intervals must be the ones of the plain loop over every triangle.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "core/field/field_program.h"
#include "core/field/potential.h"
#include "core/field/skeleton.h"

using namespace animorph;

namespace {

// A bumpy sheet of cells x cells quads (two triangles each) over [-0.5, 0.5]^2 in x, z.
std::vector<Skeleton> bumpySheet(int cells, float height) {
  auto at = [&](int i, int k) {
    float u = -0.5f + float(i) / float(cells), w = -0.5f + float(k) / float(cells);
    return glm::vec3(u, height * std::sin(6.0f * u) * std::cos(5.0f * w), w);
  };
  std::vector<Skeleton> out;
  for (int k = 0; k < cells; ++k)
    for (int i = 0; i < cells; ++i) {
      Skeleton a, b;
      a.kind = b.kind = SkeletonKind::Triangle;
      a.p0 = at(i, k), a.p1 = at(i + 1, k), a.p2 = at(i + 1, k + 1);
      b.p0 = at(i, k), b.p1 = at(i + 1, k + 1), b.p2 = at(i, k + 1);
      out.push_back(a);
      out.push_back(b);
    }
  return out;
}

struct Plain {
  float f = 0.0f;
  glm::vec3 g{0.0f};
};

// The union as the plain loop computes it: every triangle in order, the first largest value kept.
Plain plainUnion(const FieldProgram& p, uint32_t first, uint32_t count, const glm::vec3& q) {
  Plain r;
  for (uint32_t i = first; i < first + count; ++i) {
    const SkeletalPrimitive& s = p.skeletal[i];
    glm::vec3 d = q - closestOnTriangle(q, s.skeleton.p0, s.skeleton.p1, s.skeleton.p2);
    float gf;
    float v = skeletalPotential(glm::dot(d, d), s.radius, s.intensity, s.stiffness, gf);
    if (v > r.f) {
      r.f = v;
      r.g = gf * d;
    }
  }
  return r;
}

// The interval of the union over a ball as the plain loop computes it.
Interval plainInterval(const FieldProgram& p, uint32_t first, uint32_t count, const glm::vec3& c, float rho) {
  Interval acc{0.0f, 0.0f};
  for (uint32_t i = first; i < first + count; ++i) {
    const SkeletalPrimitive& s = p.skeletal[i];
    float d = glm::length(c - closestOnTriangle(c, s.skeleton.p0, s.skeleton.p1, s.skeleton.p2));
    float gf;
    float g0 = skeletalPotential(std::max(0.0f, d - rho) * std::max(0.0f, d - rho), s.radius, s.intensity, s.stiffness, gf);
    float g1 = skeletalPotential((d + rho) * (d + rho), s.radius, s.intensity, s.stiffness, gf);
    acc = {std::max(acc.lo, std::min(g0, g1)), std::max(acc.hi, std::max(g0, g1))};
  }
  return {acc.lo - p.threshold, acc.hi - p.threshold};
}

// One program holding a union of the sheet's triangles, with the radius of every triangle or, when
// `mixed`, a few different ones (the general loop then runs).
FieldProgram sheetUnion(const std::vector<Skeleton>& sheet, bool mixed) {
  FieldProgram p;
  p.threshold = 0.5f;
  for (size_t i = 0; i < sheet.size(); ++i) {
    SkeletalPrimitive s;
    s.skeleton = sheet[i];
    s.radius = mixed && i % 5 == 0 ? 0.11f : 0.09f;
    s.intensity = 1.0f;
    s.stiffness = 3.0f;
    p.addSkeletal(s, i > 0, true);
  }
  p.finish();
  return p;
}

}  // namespace

TEST_CASE("a union of triangles sharing their parameters gives the plain loop's values, gradients and intervals",
          "[field_program]") {
  const std::vector<Skeleton> sheet = bumpySheet(14, 0.08f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.6f, 0.6f), h(-0.15f, 0.15f);
  for (bool mixed : {false, true}) {
    FieldProgram p = sheetUnion(sheet, mixed);
    REQUIRE(p.ops.size() == 1);
    const uint32_t count = p.ops[0].count;
    REQUIRE(count == sheet.size());
    ActiveProgram all;
    p.specialiseAll(all);
    FieldEvaluator ev;
    int reached = 0, compared = 0;
    // Runs of 5^3 grid points (a polygoniser's sub-block) at random places near the sheet.
    for (int r = 0; r < 40; ++r) {
      const glm::vec3 corner(u(rng), h(rng), u(rng));
      const float step = r % 2 ? 0.02f : 0.045f;
      std::vector<float> x, y, z;
      for (int k = 0; k < 5; ++k)
        for (int j = 0; j < 5; ++j)
          for (int i = 0; i < 5; ++i) {
            x.push_back(corner.x + step * float(i));
            y.push_back(corner.y + step * float(j));
            z.push_back(corner.z + step * float(k));
          }
      const int n = int(x.size());
      const size_t m = x.size();
      std::vector<float> f(m), v(m), gx(m), gy(m), gz(m);
      ev.evaluate(p, all, x.data(), y.data(), z.data(), n, v.data());
      ev.evaluate(p, all, x.data(), y.data(), z.data(), n, f.data(), gx.data(), gy.data(), gz.data());
      for (int j = 0; j < n; ++j) {
        const glm::vec3 q(x[size_t(j)], y[size_t(j)], z[size_t(j)]);
        const Plain want = plainUnion(p, 0, count, q);
        INFO("run " << r << " point " << j << (mixed ? " (mixed radii)" : ""));
        CHECK(v[size_t(j)] == want.f - p.threshold);  // bit for bit
        CHECK(f[size_t(j)] == want.f - p.threshold);
        CHECK(gx[size_t(j)] == want.g.x);
        CHECK(gy[size_t(j)] == want.g.y);
        CHECK(gz[size_t(j)] == want.g.z);
        reached += want.f > 0.0f;
        ++compared;
      }
      const glm::vec3 centre = corner + 2.0f * step;
      for (float rho : {0.01f, 0.05f, 0.2f}) {
        const Interval got = p.interval(all, centre, rho), want = plainInterval(p, 0, count, centre, rho);
        CHECK(got.lo == want.lo);
        CHECK(got.hi == want.hi);
      }
    }
    // The runs meet the sheet's surface and leave it: both kinds of points were compared.
    CHECK(reached > compared / 8);
    CHECK(reached < compared);
  }
}
