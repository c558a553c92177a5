#include "util/reference_field.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/blobtree/meta_primitives.h"
#include "core/field/convolution_segment.h"
#include "core/field/operators.h"
#include "core/field/potential.h"
#include "core/field/skeleton.h"
#include "core/field/space_map.h"

namespace animorph::test {

namespace {

struct Value {
  float p = 0.0f;
  glm::vec3 g{0.0f};
};

struct Ref {
  double t;
  float T;
  float eps;

  float f(const BlobNode& n, const char* name) const { return n.floatParam(name).evaluate(t); }
  glm::vec3 v(const BlobNode& n, const char* name) const { return n.vec3Param(name).evaluate(t); }

  Value skeletal(const Skeleton& s, float R, float I, float k, const glm::vec3& x) const {
    glm::vec3 d = x - closestOnSkeleton(s, x);
    float gf;
    Value r;
    r.p = skeletalPotential(glm::dot(d, d), std::max(0.0f, R), I, std::max(0.0f, k), gf);
    r.g = gf * d;
    return r;
  }

  Value mapped(const SpaceMap& m, const std::vector<BlobNode>& children, const glm::vec3& x) const {
    glm::mat3 J;
    glm::vec3 local = m.toLocal(x, &J);
    Value sum;
    for (const auto& c : children) {
      Value cv = eval(c, local);
      sum.p += cv.p;
      sum.g += cv.g;
    }
    sum.g = glm::transpose(J) * sum.g;
    return sum;
  }

  Value eval(const BlobNode& n, const glm::vec3& x) const {
    Skeleton s;
    switch (n.type) {
      case NodeType::Point:
        s.kind = SkeletonKind::Point;
        s.p0 = v(n, "center");
        break;
      case NodeType::Sphere:
        s.kind = SkeletonKind::Sphere;
        s.p0 = v(n, "center");
        s.r0 = f(n, "skeletonRadius");
        break;
      case NodeType::Segment:
        s.kind = SkeletonKind::Segment;
        s.p0 = v(n, "a");
        s.p1 = v(n, "b");
        break;
      case NodeType::Cylinder:
        s.kind = SkeletonKind::Cylinder;
        s.p0 = v(n, "a");
        s.p1 = v(n, "b");
        s.r0 = f(n, "skeletonRadius");
        break;
      case NodeType::Cone:
        s.kind = SkeletonKind::Cone;
        s.p0 = v(n, "a");
        s.p1 = v(n, "b");
        s.r0 = f(n, "radiusA");
        s.r1 = f(n, "radiusB");
        break;
      case NodeType::Disc:
      case NodeType::Circle:
        s.kind = n.type == NodeType::Disc ? SkeletonKind::Disc : SkeletonKind::Circle;
        s.p0 = v(n, "center");
        s.p1 = glm::normalize(v(n, "normal"));
        s.r0 = f(n, "skeletonRadius");
        break;
      case NodeType::Triangle:
        s.kind = SkeletonKind::Triangle;
        s.p0 = v(n, "a");
        s.p1 = v(n, "b");
        s.p2 = v(n, "c");
        break;
      case NodeType::Curve: {
        std::vector<glm::vec3> pts = evaluatePoints(n.pointsParam("points"), t);
        s.kind = SkeletonKind::Curve;
        s.curve = pts.data();
        s.curveCount = int(pts.size());
        return skeletal(s, f(n, "radius"), f(n, "intensity"), f(n, "stiffness"), x);
      }
      case NodeType::ConvSegment: {
        glm::dvec3 a(v(n, "a")), b(v(n, "b")), xd(x);
        double len = glm::length(b - a);
        glm::dvec3 dir = len > 1e-12 ? (b - a) / len : glm::dvec3(1, 0, 0);
        double S = f(n, "sharpness");
        double R = std::max(0.0f, f(n, "radius"));
        double w = double(float(convolutionWeightForRadius(R, S, T)));
        double cut = convolutionCutoffRadius(len, S, convolutionWeightForRadius(R, S, T), T, eps);
        Value r;
        double dseg = glm::length(x - closestOnSegment(x, glm::vec3(a), glm::vec3(b)));
        if (dseg > cut) return r;
        glm::dvec3 grad;
        double F = convolutionSegmentField<double>(xd, a, dir, len, S, &grad);
        r.p = float(w * F);
        r.g = glm::vec3(w * grad);
        return r;
      }
      case NodeType::Capsule: {
        glm::vec3 a = v(n, "a"), b = v(n, "b");
        float R = std::max(0.0f, f(n, "radius"));
        glm::vec3 d = x - closestOnSegment(x, a, b);
        float dist = glm::length(d);
        Value r;
        if (R <= 0.0f) return r;
        float p = T * (2.0f - dist / R);
        if (p <= 0.0f) return r;
        r.p = p;
        r.g = dist > 0.0f ? (-T / (R * dist)) * d : glm::vec3(0.0f);
        return r;
      }
      case NodeType::Blend:
      case NodeType::Union:
      case NodeType::Intersection: {
        Value acc;
        bool first = true;
        for (const auto& c : n.children) {
          Value cv = eval(c, x);
          if (n.type == NodeType::Blend) {
            acc.p += cv.p;
            acc.g += cv.g;
          } else if (first || (n.type == NodeType::Union ? cv.p > acc.p : cv.p < acc.p)) {
            acc = cv;
          }
          first = false;
        }
        return acc;
      }
      case NodeType::HyperBlend: {
        std::vector<Value> vs;
        std::vector<float> ps, d(n.children.size());
        for (const auto& c : n.children) {
          vs.push_back(eval(c, x));
          ps.push_back(vs.back().p);
        }
        Value r;
        r.p = hyperBlend(ps.data(), int(ps.size()), std::max(1.0f, f(n, "q")), d.data());
        for (size_t i = 0; i < vs.size(); ++i) r.g += d[i] * vs[i].g;
        return r;
      }
      case NodeType::Difference: {
        Value a = eval(n.children[0], x);
        Value rest;
        for (size_t i = 1; i < n.children.size(); ++i) {
          Value c = eval(n.children[i], x);
          if (i == 1 || c.p > rest.p) rest = c;
        }
        if (2.0f * T - rest.p < a.p) return {2.0f * T - rest.p, -rest.g};
        return a;
      }
      case NodeType::RUnion:
      case NodeType::RIntersection: {
        Value a = eval(n.children[0], x), b = eval(n.children[1], x);
        float d1, d2;
        float r = n.type == NodeType::RUnion ? rUnion(a.p - T, b.p - T, d1, d2) : rIntersection(a.p - T, b.p - T, d1, d2);
        return {T + r, d1 * a.g + d2 * b.g};
      }
      case NodeType::BoundedBlend: {
        Value a = eval(n.children[0], x), b = eval(n.children[1], x), c = eval(n.children[2], x);
        BoundedBlendParams bp{f(n, "a0"), f(n, "a1"), f(n, "a2"), f(n, "a3")};
        float d[3];
        float r = boundedBlend(a.p - T, b.p - T, c.p - T, bp, d);
        return {T + r, d[0] * a.g + d[1] * b.g + d[2] * c.g};
      }
      case NodeType::Frame:
        return mapped(makeAffineMap(v(n, "translation"), n.quatParam("rotation").evaluate(t), v(n, "scale")),
                      n.children, x);
      case NodeType::Twist: return mapped(makeTwistMap(v(n, "a"), v(n, "b"), f(n, "angle")), n.children, x);
      case NodeType::Taper:
        return mapped(makeTaperMap(v(n, "a"), v(n, "b"), f(n, "scaleA"), f(n, "scaleB")), n.children, x);
      case NodeType::Bend:
        return mapped(makeBendMap(v(n, "a"), v(n, "b"), f(n, "angle"), v(n, "direction")), n.children, x);
      case NodeType::SplineOfNodes: {
        Value sum;
        for (const SpaceMap& m : splineOfNodesFrames(n, t)) {
          Value c = mapped(m, n.children, x);
          sum.p += c.p;
          sum.g += c.g;
        }
        return sum;
      }
      case NodeType::CoonsPatch: {
        Value best;
        for (const auto& tri : coonsPatchTriangles(n, t)) {
          Skeleton ts;
          ts.kind = SkeletonKind::Triangle;
          ts.p0 = tri[0];
          ts.p1 = tri[1];
          ts.p2 = tri[2];
          Value c = skeletal(ts, f(n, "radius"), f(n, "intensity"), f(n, "stiffness"), x);
          if (c.p > best.p) best = c;
        }
        return best;
      }
    }
    return skeletal(s, f(n, "radius"), f(n, "intensity"), f(n, "stiffness"), x);
  }
};

}  // namespace

float referenceField(const BlobTree& tree, double timeSec, const glm::vec3& x, glm::vec3* gradient,
                     float cutoffEpsilon) {
  Ref r{timeSec, std::max(1e-6f, tree.threshold.evaluate(timeSec)), cutoffEpsilon};
  Value v = r.eval(tree.root, x);
  if (gradient) *gradient = v.g;
  return v.p - r.T;
}

}  // namespace animorph::test
