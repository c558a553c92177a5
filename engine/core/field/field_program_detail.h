#pragma once
// Geometry tests shared by the parts of FieldProgram that cull primitives (specialising a program
// to a region, bounding the field over a region): internal to engine/core/field.
#include <glm/glm.hpp>

#include "field/convolution_segment.h"
#include "math/bounds.h"

namespace animorph::field_detail {

inline float distToSegment(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b) {
  return glm::length(x - closestOnSegment(x, a, b));
}

// The closed boxes share a point (false when either is empty).
inline bool boxesOverlap(const Bounds& a, const Bounds& box) {
  return !(a.min.x > box.max.x || a.max.x < box.min.x || a.min.y > box.max.y || a.max.y < box.min.y ||
           a.min.z > box.max.z || a.max.z < box.min.z);
}

}  // namespace animorph::field_detail
