#pragma once
// Skeletal potential g(d) = I (1 - (d/R)^2)^k for d < R, else 0 (docs/design.md §3):
// radius of influence R, intensity I, stiffness k (k = 3 is Wyvill's cubic).
#include <cmath>

namespace animorph {

// (base)^k with a multiply chain for small integer k (the common case).
inline float powStiffness(float base, float k) {
  int ki = int(k);
  if (float(ki) == k && ki >= 0 && ki <= 8) {
    float r = 1.0f;
    for (int i = 0; i < ki; ++i) r *= base;
    return r;
  }
  return std::pow(base, k);
}

// g at squared distance d2. gradFactor receives the factor f such that
// grad g = f * (x - closestSkeletonPoint); 0 outside the support.
inline float skeletalPotential(float d2, float radius, float intensity, float stiffness, float& gradFactor) {
  float r2 = radius * radius;
  if (!(d2 < r2) || r2 <= 0.0f) {
    gradFactor = 0.0f;
    return 0.0f;
  }
  float t = 1.0f - d2 / r2;
  float tk1 = stiffness == 0.0f ? 0.0f : powStiffness(t, stiffness - 1.0f);
  gradFactor = -2.0f * intensity * stiffness / r2 * tk1;
  return stiffness == 0.0f ? intensity : intensity * tk1 * t;
}

}  // namespace animorph
