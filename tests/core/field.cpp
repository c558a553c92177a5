#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include "core/blobtree/compile.h"
#include "core/field/convolution_segment.h"
#include "core/field/field_program.h"
#include "core/field/operators.h"
#include "core/field/skeleton.h"
#include "core/field/space_map.h"
#include "core/field/spline_curve.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// Composite Simpson integral of the Cauchy kernel along the segment.
double numericConvolution(glm::dvec3 x, glm::dvec3 b, glm::dvec3 a, double l, double S) {
  const int n = 200000;
  double h = l / n, sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    glm::dvec3 c = b + a * (i * h);
    double r2 = glm::dot(x - c, x - c);
    double k = 1.0 / ((1.0 + S * S * r2) * (1.0 + S * S * r2));
    sum += k * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  return sum * h / 3.0;
}

glm::vec3 randomIn(std::mt19937& rng, float s) {
  std::uniform_real_distribution<float> u(-s, s);
  return {u(rng), u(rng), u(rng)};
}

}  // namespace

TEST_CASE("convolution segment closed form equals numerical integration", "[field]") {
  std::mt19937 rng(3);
  glm::dvec3 b(0.1, -0.2, 0.05);
  glm::dvec3 a = glm::normalize(glm::dvec3(1.0, 0.5, -0.3));
  for (double S : {2.0, 10.0, 40.0}) {
    for (double l : {0.05, 0.4, 1.5}) {
      for (int i = 0; i < 12; ++i) {
        glm::dvec3 x = b + glm::dvec3(randomIn(rng, 1.0f)) * (i < 6 ? 0.2 : 1.5);
        double exact = numericConvolution(x, b, a, l, S);
        double closed = convolutionSegmentField<double>(x, b, a, l, S);
        INFO("S " << S << " l " << l << " x " << x.x << " " << x.y << " " << x.z);
        CHECK(std::abs(closed - exact) / exact <= 1e-5);
      }
    }
  }
  // Points on the axis beyond both ends and on the segment itself.
  for (double u : {-0.5, 0.0, 0.2, 0.4, 0.9}) {
    glm::dvec3 x = b + a * u;
    double exact = numericConvolution(x, b, a, 0.4, 10.0);
    CHECK(std::abs(convolutionSegmentField<double>(x, b, a, 0.4, 10.0) - exact) / exact <= 1e-5);
  }
}

TEST_CASE("convolution segment analytic gradient equals central differences", "[field]") {
  std::mt19937 rng(4);
  glm::dvec3 b(0.0), a = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
  for (int i = 0; i < 50; ++i) {
    glm::dvec3 x(randomIn(rng, 0.8f));
    glm::dvec3 g;
    convolutionSegmentField<double>(x, b, a, 0.6, 7.0, &g);
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 e(0.0);
      e[k] = h;
      double fd = (convolutionSegmentField<double>(x + e, b, a, 0.6, 7.0) -
                   convolutionSegmentField<double>(x - e, b, a, 0.6, 7.0)) / (2 * h);
      CHECK(g[k] == Approx(fd).margin(1e-6 * std::max(1.0, glm::length(g))).epsilon(1e-5));
    }
  }
}

TEST_CASE("the radius rule puts the surface of a long segment at R within 1%", "[field]") {
  const double T = 0.8;
  for (double S : {3.0, 10.0, 30.0}) {
    for (double R : {0.05, 0.1, 0.3}) {
      double l = 40.0 * R + 20.0 / S;  // long against both the radius and the kernel width
      double w = convolutionWeightForRadius(R, S, T);
      glm::dvec3 b(0.0), a(1, 0, 0);
      auto f = [&](double r) { return w * convolutionSegmentField<double>(glm::dvec3(0.5 * l, r, 0), b, a, l, S) - T; };
      double lo = 0.0, hi = 10.0 * R;
      REQUIRE(f(lo) > 0.0);
      REQUIRE(f(hi) < 0.0);
      for (int i = 0; i < 80; ++i) (f(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
      INFO("S " << S << " R " << R);
      CHECK(std::abs(lo - R) / R < 0.01);
    }
  }
}

TEST_CASE("the batched convolution kernel matches the closed form", "[field]") {
  FieldProgram p;
  p.threshold = 1.0f;
  glm::vec3 a(0.1f, 0.0f, -0.2f), b(0.5f, 0.3f, 0.1f);
  p.addConvolution(a, b, 0.1f, 8.0f, 1e-9f, false);
  p.finish();
  double w = convolutionWeightForRadius(0.1, 8.0, 1.0);
  std::mt19937 rng(5);
  FieldEvaluator ev;
  glm::dvec3 dir = glm::normalize(glm::dvec3(b - a));
  double len = glm::length(glm::dvec3(b - a));
  for (int i = 0; i < 300; ++i) {
    glm::vec3 x = randomIn(rng, 1.0f);
    glm::vec3 g;
    float f = ev.evaluatePoint(p, x, &g);
    glm::dvec3 ge;
    double exact = w * convolutionSegmentField<double>(glm::dvec3(x), glm::dvec3(a), dir, len, 8.0, &ge) - 1.0;
    CHECK(std::abs(f - exact) <= 1e-5 * std::max(1.0, std::abs(exact) + 1.0));
    CHECK(glm::length(glm::dvec3(g) - w * ge) <= 1e-4 * std::max(1.0, w * glm::length(ge)));
  }
  // The cut: beyond the bound the contribution is exactly zero, and it was below eps * T.
  FieldProgram q;
  q.threshold = 1.0f;
  q.addConvolution(a, b, 0.1f, 8.0f, 1e-3f, false);
  q.finish();
  float cut = std::sqrt(q.convolution.cut2[0]);
  glm::vec3 mid = 0.5f * (a + b), perp = glm::normalize(glm::cross(b - a, glm::vec3(0, 0, 1)));
  CHECK(ev.evaluatePoint(q, mid + perp * (cut * 1.01f)) == -1.0f);
  float inside = ev.evaluatePoint(q, mid + perp * (cut * 0.99f)) + 1.0f;
  CHECK(inside > 0.0f);
  CHECK(inside < 1.2e-3f);
}

TEST_CASE("closest points on every skeleton beat dense sampling", "[field]") {
  std::mt19937 rng(6);
  std::vector<glm::vec3> curve = {{-0.5f, 0, 0}, {-0.1f, 0.3f, 0.1f}, {0.2f, -0.2f, 0}, {0.5f, 0.1f, 0.3f}};
  std::vector<Skeleton> skels(9);
  skels[0].kind = SkeletonKind::Point;
  skels[0].p0 = {0.1f, 0.2f, 0};
  skels[1] = {SkeletonKind::Sphere, {0, 0, 0}, {}, {}, 0.3f};
  skels[2] = {SkeletonKind::Segment, {-0.3f, 0, 0}, {0.4f, 0.2f, 0.1f}};
  skels[3] = {SkeletonKind::Cylinder, {-0.3f, 0, 0}, {0.4f, 0.2f, 0.1f}, {}, 0.15f};
  skels[4] = {SkeletonKind::Cone, {-0.3f, 0, 0}, {0.4f, 0.2f, 0.1f}, {}, 0.25f, 0.05f};
  skels[5] = {SkeletonKind::Disc, {0, 0.1f, 0}, glm::normalize(glm::vec3(0.2f, 1, 0)), {}, 0.3f};
  skels[6] = {SkeletonKind::Circle, {0, 0.1f, 0}, glm::normalize(glm::vec3(0.2f, 1, 0)), {}, 0.3f};
  skels[7] = {SkeletonKind::Triangle, {-0.3f, 0, 0}, {0.3f, 0.1f, 0}, {0, 0.2f, 0.4f}};
  skels[8].kind = SkeletonKind::Curve;
  skels[8].curve = curve.data();
  skels[8].curveCount = int(curve.size());
  for (const Skeleton& s : skels) {
    // Brute force: sample the skeleton directly by its own parametrisation.
    std::vector<glm::vec3> pts;
    const int n = 60;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        float u = float(i) / n, v = float(j) / n;
        switch (s.kind) {
          case SkeletonKind::Point: pts.push_back(s.p0); break;
          case SkeletonKind::Sphere: {
            float th = u * 6.2831853f, ph = v * 3.1415926f;
            pts.push_back(s.p0 + s.r0 * glm::vec3(std::sin(ph) * std::cos(th), std::cos(ph), std::sin(ph) * std::sin(th)));
            break;
          }
          case SkeletonKind::Segment: pts.push_back(glm::mix(s.p0, s.p1, u)); break;
          case SkeletonKind::Cylinder:
          case SkeletonKind::Cone:
          case SkeletonKind::Disc:
          case SkeletonKind::Circle: {
            glm::vec3 ax = s.kind == SkeletonKind::Disc || s.kind == SkeletonKind::Circle ? s.p1 : glm::normalize(s.p1 - s.p0);
            glm::vec3 e1 = glm::normalize(glm::cross(ax, glm::vec3(0.3f, 0.5f, 0.8f)));
            glm::vec3 e2 = glm::cross(ax, e1);
            float th = u * 6.2831853f;
            glm::vec3 rd = std::cos(th) * e1 + std::sin(th) * e2;
            if (s.kind == SkeletonKind::Circle) pts.push_back(s.p0 + s.r0 * rd);
            else if (s.kind == SkeletonKind::Disc) pts.push_back(s.p0 + v * s.r0 * rd);
            else {
              float rr = s.kind == SkeletonKind::Cone ? glm::mix(s.r0, s.r1, v) : s.r0;
              glm::vec3 c = glm::mix(s.p0, s.p1, v);
              pts.push_back(c + rr * rd);        // mantle
              pts.push_back(s.p0 + u * s.r0 * rd);  // caps
              pts.push_back(s.p1 + u * (s.kind == SkeletonKind::Cone ? s.r1 : s.r0) * rd);
            }
            break;
          }
          case SkeletonKind::Triangle:
            if (u + v <= 1.0f) pts.push_back(s.p0 + u * (s.p1 - s.p0) + v * (s.p2 - s.p0));
            break;
          case SkeletonKind::Curve:
            pts.push_back(evaluateCurve(s.curve, s.curveCount, float(i * (n + 1) + j) / float((n + 1) * (n + 1) - 1)).position);
            break;
        }
      }
    for (int k = 0; k < 60; ++k) {
      glm::vec3 x = randomIn(rng, 1.0f);
      glm::vec3 c = closestOnSkeleton(s, x);
      float d = glm::length(x - c);
      float best = INFINITY;
      for (const auto& p : pts) best = std::min(best, glm::length(x - p));
      INFO("kind " << int(s.kind));
      CHECK(d <= best + 1e-4f);     // never worse than any sampled skeleton point
      CHECK(d >= best - 0.03f);     // and a point of the skeleton (within the sampling density)
    }
  }
}

TEST_CASE("space maps: round trip and analytic Jacobians", "[field]") {
  std::vector<SpaceMap> maps = {
      makeAffineMap({0.1f, -0.2f, 0.3f}, glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3))), {1.5f, 0.5f, 2.0f}),
      makeTwistMap({0, -0.5f, 0}, {0.1f, 0.5f, 0}, 2.0f),
      makeTaperMap({0, -0.5f, 0}, {0, 0.5f, 0.1f}, 0.5f, 1.5f),
      makeBendMap({0, -0.5f, 0}, {0, 0.5f, 0}, 1.0f, {1, 0, 0}),
      makeBendMap({0, -0.5f, 0}, {0, 0.5f, 0}, -0.8f, {0, 0, 1}),
  };
  std::mt19937 rng(8);
  for (size_t m = 0; m < maps.size(); ++m) {
    for (int i = 0; i < 100; ++i) {
      glm::vec3 c = randomIn(rng, 0.4f);
      glm::vec3 w = maps[m].toWorld(c);
      INFO("map " << m);
      CHECK(glm::length(maps[m].toLocal(w) - c) < 2e-5f);
      glm::mat3 J;
      maps[m].toLocal(w, &J);
      const float h = 1e-3f;
      for (int k = 0; k < 3; ++k) {
        glm::vec3 e(0.0f);
        e[k] = h;
        glm::vec3 fd = (maps[m].toLocal(w + e) - maps[m].toLocal(w - e)) / (2.0f * h);
        CHECK(glm::length(fd - J[k]) < 5e-3f * std::max(1.0f, glm::length(fd)));
      }
    }
  }
}

TEST_CASE("R-function identities and bounded blending", "[field]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  for (int i = 0; i < 500; ++i) {
    float a = u(rng), b = u(rng), d1, d2, e1, e2;
    float uni = rUnion(a, b, d1, d2);
    float inter = rIntersection(a, b, e1, e2);
    CHECK(uni == Approx(-rIntersection(-a, -b, e1, e2)).margin(1e-5));  // De Morgan
    CHECK(uni == Approx(rUnion(b, a, e1, e2)).margin(1e-6));            // symmetric
    CHECK((uni > 0.0f) == (std::max(a, b) > 0.0f));                      // same solid as max
    CHECK((inter >= 0.0f) == (std::min(a, b) >= 0.0f));                  // same solid as min
    CHECK(uni + inter == Approx(2.0f * (a + b)).margin(1e-5));
    // Outside its bounding solid (s3 <= 0) bounded blending is the plain union.
    BoundedBlendParams p{0.7f, 1.0f, 1.2f, 0.5f};
    float dd[3];
    float s3 = -std::abs(u(rng));
    CHECK(boundedBlend(a, b, s3, p, dd) == rUnion(a, b, d1, d2));
    // Inside, it only adds material, at most a0.
    float in = boundedBlend(a, b, std::abs(u(rng)) + 0.01f, p, dd);
    CHECK(in >= uni);
    CHECK(in <= uni + p.a0 + 1e-6f);
  }
  float dd[3];
  CHECK(boundedBlend(0.0f, 0.0f, 1.0f, {0.7f, 1, 1, 1}, dd) == Approx(0.7f));  // r = 0: full a0
}

TEST_CASE("bounded blend node equals the R-union node outside its bounding child", "[field]") {
  BlobNode p1 = pointNode(2, {-0.2f, 0, 0}, 0.4f), p2 = pointNode(3, {0.2f, 0, 0}, 0.4f);
  BlobNode bound = pointNode(4, {0, 0.3f, 0}, 0.25f);
  BlobNode bb = operatorNode(NodeType::BoundedBlend, 1, {p1, p2, bound});
  bb.floatParam("a0") = FloatTrack(0.5f);
  FieldProgram blended = compileFieldProgram(treeOf(bb), 0.0);
  FieldProgram plain = compileFieldProgram(treeOf(operatorNode(NodeType::RUnion, 1, {p1, p2})), 0.0);
  FieldProgram boundOnly = compileFieldProgram(treeOf(bound), 0.0);
  FieldEvaluator ev;
  std::mt19937 rng(10);
  int inside = 0;
  for (int i = 0; i < 400; ++i) {
    glm::vec3 x = i % 2 ? randomIn(rng, 0.7f) : glm::vec3(0, 0.3f, 0) + randomIn(rng, 0.15f);
    float fb = ev.evaluatePoint(blended, x), fp = ev.evaluatePoint(plain, x);
    if (ev.evaluatePoint(boundOnly, x) <= 0.0f) CHECK(fb == fp);
    else {
      ++inside;
      CHECK(fb >= fp);
    }
  }
  CHECK(inside > 5);
}

TEST_CASE("gradients of every node type equal central differences", "[field]") {
  std::mt19937 rng(11);
  for (const NodeTypeInfo& info : allNodeTypes()) {
    // A node of this type (random primitive parameters, or an operator / map /
    // meta node over random children) whose field is non-trivial somewhere.
    int checked = 0, agree = 0;
    for (int attempt = 0; attempt < 2000 && checked < 30; ++attempt) {
      int id = 1;
      BlobNode node = randomNode(rng, 2, id);
      if (node.type != info.type) continue;
      FieldProgram p = compileFieldProgram(treeOf(node), 0.3, CompileOptions{1e-7f});
      Bounds b = p.bounds();
      if (b.empty()) continue;
      FieldEvaluator ev;
      checked = agree = 0;
      std::uniform_real_distribution<float> u01(0.0f, 1.0f);
      for (int i = 0; i < 3000 && checked < 150; ++i) {
        glm::vec3 x = b.min + (b.max - b.min) * glm::vec3(u01(rng), u01(rng), u01(rng));
        glm::vec3 g;
        float f = ev.evaluatePoint(p, x, &g);
        if (glm::length(g) < 1e-6f) continue;  // flat here (no primitive reaches x): nothing to check
        (void)f;
        const float h = 2e-4f;
        glm::vec3 fd;
        for (int k = 0; k < 3; ++k) {
          glm::vec3 e(0.0f);
          e[k] = h;
          fd[k] = (ev.evaluatePoint(p, x + e) - ev.evaluatePoint(p, x - e)) / (2.0f * h);
        }
        ++checked;
        if (glm::length(fd - g) <= 2e-2f * std::max(1.0f, glm::length(fd))) ++agree;
      }
    }
    INFO(info.name << ": " << agree << " of " << checked << " points agree");
    CHECK(checked >= 30);
    // Kinks (max/min switches, medial axes, clamps) are measure-zero sets that
    // a finite-difference stencil straddles now and then.
    CHECK(agree >= checked * 97 / 100);
  }
}

TEST_CASE("curve positions alone equal evaluateCurve's positions bit for bit", "[field]") {
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> d(-3.0f, 3.0f);
  std::uniform_real_distribution<float> param(-0.2f, 1.2f);
  int mismatches = 0, checked = 0;
  for (int n = 0; n <= 6; ++n) {
    std::vector<glm::vec3> pts(static_cast<size_t>(n));
    for (int trial = 0; trial < 50; ++trial) {
      for (glm::vec3& p : pts) p = glm::vec3(d(rng), d(rng), d(rng));
      for (float s : {0.0f, 1.0f, 0.5f, param(rng), param(rng), param(rng)}) {
        const glm::vec3 got = curvePosition(pts, s), want = evaluateCurve(pts, s).position;
        mismatches += std::memcmp(&got, &want, sizeof got) == 0 ? 0 : 1;
        ++checked;
      }
    }
  }
  CHECK(checked == 7 * 50 * 6);
  CHECK(mismatches == 0);
}
