#pragma once
// Scalar forms of the field operators with gradients (docs/design.md §3). They act
// on signed values s = p - T (>= 0 inside) for the R-functions and bounded
// blending; the BlobTree operators blend / hyper-blend / union / intersection
// / difference act on potentials p. Used by the reference evaluator, the
// batched FieldProgram and the interval bounds alike.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace animorph {

// Remap of a potential p (one operand): scale * p, or with a saturation level
// K > 1 (in units of T) scale * K T p+ / ((K - 1) T + p+) with p+ = max(p, 0):
// monotone, h(0) = 0, h(T) = T (the surface p = T is kept at scale 1) and
// bounded by K T, so that a remnant (1 - w) h(p1) >= T of a field fading out
// of a morph shrinks to nothing at w = 1 - 1/K instead of lingering near its
// skeleton until w = 1 (standin_morph/morph_field.h). d receives dh/dp.
inline float remapPotential(float p, float scale, float K, float T, float& d) {
  if (!(K > 1.0f)) {
    d = scale;
    return scale * p;
  }
  if (!(p > 0.0f)) {
    d = scale * K / (K - 1.0f);
    return scale * K * T * std::min(p, 0.0f) / ((K - 1.0f) * T);
  }
  const float den = (K - 1.0f) * T + p;
  d = scale * K * (K - 1.0f) * T * T / (den * den);
  return scale * K * T * p / den;
}

// R-function union s1 + s2 + sqrt(s1^2 + s2^2); d1, d2 receive the partial derivatives.
inline float rUnion(float s1, float s2, float& d1, float& d2) {
  float r = std::sqrt(s1 * s1 + s2 * s2);
  if (r > 0.0f) {
    d1 = 1.0f + s1 / r;
    d2 = 1.0f + s2 / r;
  } else {
    d1 = d2 = 1.0f;
  }
  return s1 + s2 + r;
}

// R-function intersection s1 + s2 - sqrt(s1^2 + s2^2).
inline float rIntersection(float s1, float s2, float& d1, float& d2) {
  float r = std::sqrt(s1 * s1 + s2 * s2);
  if (r > 0.0f) {
    d1 = 1.0f - s1 / r;
    d2 = 1.0f - s2 / r;
  } else {
    d1 = d2 = 1.0f;
  }
  return s1 + s2 - r;
}

struct BoundedBlendParams {
  float a0 = 1.0f, a1 = 1.0f, a2 = 1.0f, a3 = 1.0f;
};

// Pasko bounded blending of s1, s2 inside the bounding solid s3:
// (s1 v s2) + a0 (1 - r)^3 / (1 + r), r = r1 / (r1 + r2). d[0..2] receive the partials.
inline float boundedBlend(float s1, float s2, float s3, const BoundedBlendParams& p, float d[3]) {
  float du1, du2;
  float u = rUnion(s1, s2, du1, du2);
  float r1 = (s1 / p.a1) * (s1 / p.a1) + (s2 / p.a2) * (s2 / p.a2);
  float r2 = s3 > 0.0f ? (s3 / p.a3) * (s3 / p.a3) : 0.0f;
  float sum = r1 + r2;
  d[0] = du1;
  d[1] = du2;
  d[2] = 0.0f;
  if (sum <= 0.0f) return u;  // r = 1 by continuity from outside the bound: no displacement
  float r = r1 / sum;
  if (r >= 1.0f) return u;
  float om = 1.0f - r;
  float disp = p.a0 * om * om * om / (1.0f + r);
  float dDisp = -p.a0 * om * om * (4.0f + 2.0f * r) / ((1.0f + r) * (1.0f + r));
  float inv = 1.0f / (sum * sum);
  // dr/ds1 = (dr1/ds1 r2) / sum^2, dr/ds3 = -(r1 dr2/ds3) / sum^2
  d[0] += dDisp * (2.0f * s1 / (p.a1 * p.a1)) * r2 * inv;
  d[1] += dDisp * (2.0f * s2 / (p.a2 * p.a2)) * r2 * inv;
  d[2] = s3 > 0.0f ? dDisp * (-r1 * 2.0f * s3 / (p.a3 * p.a3)) * inv : 0.0f;
  return u + disp;
}

// Hyper-blend (sum p_i^q)^(1/q) of non-negative potentials (negatives count as 0);
// d[i] receives the partials. q >= 1.
inline float hyperBlend(const float* p, int n, float q, float* d) {
  float sum = 0.0f;
  for (int i = 0; i < n; ++i) sum += p[i] > 0.0f ? std::pow(p[i], q) : 0.0f;
  if (sum <= 0.0f) {
    for (int i = 0; i < n; ++i) d[i] = 0.0f;
    return 0.0f;
  }
  float h = std::pow(sum, 1.0f / q);
  for (int i = 0; i < n; ++i) d[i] = p[i] > 0.0f ? std::pow(p[i] / h, q - 1.0f) : 0.0f;
  return h;
}

}  // namespace animorph
