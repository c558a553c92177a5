#pragma once
// Geometry tests shared by the parts of FieldProgram that cull primitives (specialising a program
// to a region, bounding the field over a region): internal to engine/core/field.
#include <glm/glm.hpp>

#include "core/field/convolution_segment.h"
#include "core/math/bounds.h"

// Hot loops compiled for AVX-512, AVX2 and the baseline, chosen at run time. Where the file is
// compiled with -ffp-contract=off (engine/core/CMakeLists.txt) every clone computes the same
// values; field_kernels.cpp allows contraction in its convolution kernels.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define ANIMORPH_KERNEL __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define ANIMORPH_KERNEL
#endif

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
