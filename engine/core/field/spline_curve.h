#pragma once
// Uniform Catmull-Rom curve through control points (spline-curve primitive,
// spline-of-nodes, Coons patch boundaries). Parameter s in [0, 1] over the
// whole curve; ends use mirrored phantom points so the curve interpolates all
// control points.
#include <algorithm>

#include <glm/glm.hpp>
#include <vector>

namespace animorph {

struct CurvePoint {
  glm::vec3 position;
  glm::vec3 tangent;  // dC/ds
  glm::vec3 second;   // d2C/ds2
};

// Point, first and second derivative at s (clamped to [0,1]). One control point: a constant curve.
CurvePoint evaluateCurve(const glm::vec3* points, int count, float s);
inline CurvePoint evaluateCurve(const std::vector<glm::vec3>& pts, float s) {
  return evaluateCurve(pts.data(), int(pts.size()), s);
}

// The span of the curve holding s: position p1 + u (c1 + u (c2 + u c3)) for u in [0, 1]. count >= 2.
struct CurveSpan {
  glm::vec3 p1, c1, c2, c3;
  float u;
  int spans;
  glm::vec3 position() const { return p1 + u * (c1 + u * (c2 + u * c3)); }
};
inline CurveSpan curveSpan(const glm::vec3* p, int n, float s) {
  CurveSpan c;
  c.spans = n - 1;
  float x = std::clamp(s, 0.0f, 1.0f) * float(c.spans);
  int i = std::min(int(x), c.spans - 1);
  c.u = x - float(i);
  c.p1 = p[i];
  glm::vec3 p2 = p[i + 1];
  glm::vec3 p0 = i > 0 ? p[i - 1] : 2.0f * c.p1 - p2;
  glm::vec3 p3 = i + 2 < n ? p[i + 2] : 2.0f * p2 - c.p1;
  c.c1 = 0.5f * (p2 - p0);
  c.c2 = 0.5f * (2.0f * p0 - 5.0f * c.p1 + 4.0f * p2 - p3);
  c.c3 = 0.5f * (-p0 + 3.0f * c.p1 - 3.0f * p2 + p3);
  return c;
}

// evaluateCurve's position alone (the same float operations, bit for bit), without the derivatives.
inline glm::vec3 curvePosition(const glm::vec3* points, int count, float s) {
  if (count <= 1) return count == 1 ? points[0] : glm::vec3(0.0f);
  return curveSpan(points, count, s).position();
}
inline glm::vec3 curvePosition(const std::vector<glm::vec3>& pts, float s) {
  return curvePosition(pts.data(), int(pts.size()), s);
}

// Curve parameter of the point of the curve closest to x: dense sampling, then
// Newton refinement of (C(s) - x) . C'(s) = 0 in the best sample's neighbourhood.
float closestCurveParameter(const glm::vec3* points, int count, const glm::vec3& x);

}  // namespace animorph
