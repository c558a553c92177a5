#pragma once
// Uniform Catmull-Rom curve through control points (spline-curve primitive,
// spline-of-nodes, Coons patch boundaries). Parameter s in [0, 1] over the
// whole curve; ends use mirrored phantom points so the curve interpolates all
// control points.
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

// Curve parameter of the point of the curve closest to x: dense sampling, then
// Newton refinement of (C(s) - x) . C'(s) = 0 in the best sample's neighbourhood.
float closestCurveParameter(const glm::vec3* points, int count, const glm::vec3& x);

}  // namespace animorph
