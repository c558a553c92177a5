#pragma once
// Skeletons of the skeletal primitives (docs/design.md §3) and the exact closest
// point on each. Solid skeletons (ball, cylinder, cone, disc) return x itself
// when x is inside them (distance 0). The gradient of a distance-based
// potential is then g'(d) (x - closest) / d, with no special cases.
#include <cstdint>
#include <glm/glm.hpp>

namespace animorph {

enum class SkeletonKind : uint8_t { Point, Sphere, Segment, Cylinder, Cone, Disc, Circle, Triangle, Curve };

// Plain description of one skeleton; which fields are used depends on kind.
struct Skeleton {
  SkeletonKind kind = SkeletonKind::Point;
  glm::vec3 p0{0.0f};      // point / centre / segment start / triangle a
  glm::vec3 p1{0.0f};      // segment end / triangle b / disc and circle normal (unit)
  glm::vec3 p2{0.0f};      // triangle c
  float r0 = 0.0f;         // sphere, cylinder, disc, circle radius; cone radius at p0
  float r1 = 0.0f;         // cone radius at p1
  const glm::vec3* curve = nullptr;  // spline control points (kind Curve)
  int curveCount = 0;
};

glm::vec3 closestOnSegment(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b);
glm::vec3 closestOnBall(const glm::vec3& x, const glm::vec3& c, float r);
// Solid capped cone frustum from a (radius ra) to b (radius rb); a cylinder when ra == rb.
glm::vec3 closestOnCone(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b, float ra, float rb);
glm::vec3 closestOnDisc(const glm::vec3& x, const glm::vec3& c, const glm::vec3& n, float r);
glm::vec3 closestOnCircle(const glm::vec3& x, const glm::vec3& c, const glm::vec3& n, float r);
glm::vec3 closestOnTriangle(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// Closest point of any skeleton.
glm::vec3 closestOnSkeleton(const Skeleton& s, const glm::vec3& x);

// A segment (a, b) and radius enclosing the skeleton: every skeleton point is
// within `radius` of the segment. Used for bounds and culling.
void skeletonEnclosingCapsule(const Skeleton& s, glm::vec3& a, glm::vec3& b, float& radius);

}  // namespace animorph
