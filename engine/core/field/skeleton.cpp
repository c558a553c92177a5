#include "core/field/skeleton.h"

#include <algorithm>
#include <cmath>

#include "core/field/spline_curve.h"

namespace animorph {

glm::vec3 closestOnSegment(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b) {
  glm::vec3 ab = b - a;
  float l2 = glm::dot(ab, ab);
  if (l2 <= 0.0f) return a;
  float t = std::clamp(glm::dot(x - a, ab) / l2, 0.0f, 1.0f);
  return a + t * ab;
}

glm::vec3 closestOnBall(const glm::vec3& x, const glm::vec3& c, float r) {
  glm::vec3 d = x - c;
  float l = glm::length(d);
  if (l <= r) return x;
  return c + d * (r / l);
}

namespace {

// Any unit vector perpendicular to n.
glm::vec3 anyPerpendicular(const glm::vec3& n) {
  glm::vec3 t = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(n, t));
}

// Closest point on the 2D segment p-q to point c.
glm::vec2 closest2(const glm::vec2& c, const glm::vec2& p, const glm::vec2& q) {
  glm::vec2 pq = q - p;
  float l2 = glm::dot(pq, pq);
  if (l2 <= 0.0f) return p;
  float t = std::clamp(glm::dot(c - p, pq) / l2, 0.0f, 1.0f);
  return p + t * pq;
}

}  // namespace

glm::vec3 closestOnCone(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b, float ra, float rb) {
  glm::vec3 ab = b - a;
  float len = glm::length(ab);
  if (len <= 1e-12f) return closestOnDisc(x, a, glm::vec3(0, 1, 0), std::max(ra, rb));
  glm::vec3 axis = ab / len;
  glm::vec3 d = x - a;
  float u = glm::dot(d, axis);
  glm::vec3 radial = d - u * axis;
  float rho = glm::length(radial);
  glm::vec3 rdir = rho > 1e-12f ? radial / rho : anyPerpendicular(axis);
  // The solid is the trapezoid (0,0) (0,ra) (len,rb) (len,0) in (u, rho), revolved.
  if (u >= 0.0f && u <= len && rho <= ra + (rb - ra) * (u / len)) return x;
  glm::vec2 c(u, rho);
  glm::vec2 v[4] = {{0.0f, 0.0f}, {0.0f, ra}, {len, rb}, {len, 0.0f}};
  glm::vec2 best = v[0];
  float bestD = INFINITY;
  for (int i = 0; i < 3; ++i) {  // the edge on the axis (rho = 0) is never closest for rho >= 0
    glm::vec2 q = closest2(c, v[i], v[i + 1]);
    float dd = glm::dot(q - c, q - c);
    if (dd < bestD) {
      bestD = dd;
      best = q;
    }
  }
  return a + best.x * axis + best.y * rdir;
}

glm::vec3 closestOnDisc(const glm::vec3& x, const glm::vec3& c, const glm::vec3& n, float r) {
  glm::vec3 d = x - c;
  glm::vec3 inPlane = d - glm::dot(d, n) * n;
  float l = glm::length(inPlane);
  if (l > r) inPlane *= r / l;
  return c + inPlane;
}

glm::vec3 closestOnCircle(const glm::vec3& x, const glm::vec3& c, const glm::vec3& n, float r) {
  glm::vec3 d = x - c;
  glm::vec3 inPlane = d - glm::dot(d, n) * n;
  float l = glm::length(inPlane);
  glm::vec3 dir = l > 1e-12f ? inPlane / l : anyPerpendicular(n);
  return c + r * dir;
}

// Ericson, Real-Time Collision Detection, 5.1.5.
glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return a;
  glm::vec3 bp = p - b;
  float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
  glm::vec3 cp = p - c;
  float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
  float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  float denom = 1.0f / (va + vb + vc);
  if (!std::isfinite(denom)) return closestOnSegment(p, a, b);  // degenerate triangle
  return a + ab * (vb * denom) + ac * (vc * denom);
}

glm::vec3 closestOnSkeleton(const Skeleton& s, const glm::vec3& x) {
  switch (s.kind) {
    case SkeletonKind::Point: return s.p0;
    case SkeletonKind::Sphere: return closestOnBall(x, s.p0, s.r0);
    case SkeletonKind::Segment: return closestOnSegment(x, s.p0, s.p1);
    case SkeletonKind::Cylinder: return closestOnCone(x, s.p0, s.p1, s.r0, s.r0);
    case SkeletonKind::Cone: return closestOnCone(x, s.p0, s.p1, s.r0, s.r1);
    case SkeletonKind::Disc: return closestOnDisc(x, s.p0, s.p1, s.r0);
    case SkeletonKind::Circle: return closestOnCircle(x, s.p0, s.p1, s.r0);
    case SkeletonKind::Triangle: return closestOnTriangle(x, s.p0, s.p1, s.p2);
    case SkeletonKind::Curve:
      return evaluateCurve(s.curve, s.curveCount, closestCurveParameter(s.curve, s.curveCount, x)).position;
  }
  return s.p0;
}

void skeletonEnclosingCapsule(const Skeleton& s, glm::vec3& a, glm::vec3& b, float& radius) {
  switch (s.kind) {
    case SkeletonKind::Point: a = b = s.p0; radius = 0.0f; return;
    case SkeletonKind::Sphere: a = b = s.p0; radius = s.r0; return;
    case SkeletonKind::Segment: a = s.p0; b = s.p1; radius = 0.0f; return;
    case SkeletonKind::Cylinder: a = s.p0; b = s.p1; radius = s.r0; return;
    case SkeletonKind::Cone: a = s.p0; b = s.p1; radius = std::max(s.r0, s.r1); return;
    case SkeletonKind::Disc:
    case SkeletonKind::Circle: a = b = s.p0; radius = s.r0; return;
    case SkeletonKind::Triangle: {
      glm::vec3 c = (s.p0 + s.p1 + s.p2) / 3.0f;
      a = b = c;
      radius = std::max({glm::length(s.p0 - c), glm::length(s.p1 - c), glm::length(s.p2 - c)});
      return;
    }
    case SkeletonKind::Curve: {
      // Sample densely; pad by the largest chord sag estimate (spacing * max speed / 2).
      glm::vec3 lo(INFINITY), hi(-INFINITY);
      const int samples = std::max(2, s.curveCount) * 16;
      float maxSpeed = 0.0f;
      for (int i = 0; i <= samples; ++i) {
        CurvePoint c = evaluateCurve(s.curve, s.curveCount, float(i) / float(samples));
        lo = glm::min(lo, c.position);
        hi = glm::max(hi, c.position);
        maxSpeed = std::max(maxSpeed, glm::length(c.tangent));
      }
      a = b = 0.5f * (lo + hi);
      radius = 0.5f * glm::length(hi - lo) + maxSpeed / float(samples);
      return;
    }
  }
}

}  // namespace animorph
