#pragma once
// The float operations of one key segment of a Track, shared by Track::evaluate
// (anim/track.cpp) and its precompiled sampler (anim/track_sampler.h), so both
// compute the same values bit for bit: the Hermite-Ferguson coefficients of a
// segment, their Horner evaluation, and the shortest-arc slerp of quaternions.
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace animorph {

inline glm::quat shortArc(const glm::quat& from, const glm::quat& to) { return glm::dot(from, to) < 0.0f ? -to : to; }

// Slerp of unit quaternions along the shortest arc, stable near equal inputs.
inline glm::quat slerpShort(const glm::quat& a, const glm::quat& bIn, float s) {
  glm::quat b = shortArc(a, bIn);
  float c = glm::clamp(glm::dot(a, b), -1.0f, 1.0f);
  if (c > 0.9995f) return glm::normalize(a * (1.0f - s) + b * s);
  float theta = std::acos(c);
  float sn = std::sin(theta);
  return glm::normalize(a * (std::sin((1.0f - s) * theta) / sn) + b * (std::sin(s * theta) / sn));
}

// Coefficients c[0..degree*2-1] (degree 2: cubic, 3: quintic) in the segment's unit parameter s of
// the Hermite segment from p0 (derivatives v0, a0) to p1 (v1, a1) over h seconds.
template <class T>
void hermiteCoefficients(const T& p0, const T& p1, const T& v0, const T& a0, const T& v1, const T& a1, float h,
                         int degree, T c[6]) {
  T dp = p1 - p0;
  c[0] = p0;
  c[1] = v0 * h;
  if (degree == 2) {
    c[2] = dp * 3.0f - v0 * (2.0f * h) - v1 * h;
    c[3] = dp * -2.0f + v0 * h + v1 * h;
    return;
  }
  float h2 = h * h;
  c[2] = a0 * (0.5f * h2);
  c[3] = dp * 10.0f - v0 * (6.0f * h) - v1 * (4.0f * h) - a0 * (1.5f * h2) + a1 * (0.5f * h2);
  c[4] = dp * -15.0f + v0 * (8.0f * h) + v1 * (7.0f * h) + a0 * (1.5f * h2) - a1 * h2;
  c[5] = dp * 6.0f - v0 * (3.0f * h) - v1 * (3.0f * h) - a0 * (0.5f * h2) + a1 * (0.5f * h2);
}

// The segment's value at s from hermiteCoefficients.
template <class T>
T hermiteValue(const T c[6], int degree, float s) {
  if (degree == 2) return c[0] + s * (c[1] + s * (c[2] + s * c[3]));
  return c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))));
}

}  // namespace animorph
