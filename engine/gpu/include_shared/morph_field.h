// The implicit morph of two signed fields f1, f2 (>= 0 inside), docs/design.md §5,
// written once in the common subset of C++ and GLSL: the GPU polygoniser's
// shaders include it, C++ callers (CPU references, tests, the morph engine)
// call the same functions (namespace animorph::morphfield), so both sides
// evaluate the same formula.
//
//   interpolation:        m = (1 - w) f1 + w f2
//   space-time blending:  with s = timeScale,
//                         g1 = f1 ^ (-s t),  g2 = f2 ^ (s (t - 1)),
//                         m  = (g1 v g2) + disp(g1, g2, (s t) ^ (s (1 - t)))
//   where ^ / v are the R-function intersection / union and disp is Pasko's
//   bounded-blending displacement a0 (1 - r)^3 / (1 + r), r = r1 / (r1 + r2),
//   r1 = (g1/a1)^2 + (g2/a2)^2, r2 = (b/a3)^2 for b > 0, else 0.
#ifndef ANIMORPH_MORPH_FIELD_H
#define ANIMORPH_MORPH_FIELD_H

#ifdef __cplusplus
#include <cmath>
#define AM_MF_FN inline
namespace animorph::morphfield {
using std::sqrt;
#else
#define AM_MF_FN
#endif

// R-function union s1 + s2 + sqrt(s1^2 + s2^2).
AM_MF_FN float amRUnion(float s1, float s2) { return s1 + s2 + sqrt(s1 * s1 + s2 * s2); }

// R-function intersection s1 + s2 - sqrt(s1^2 + s2^2).
AM_MF_FN float amRIntersection(float s1, float s2) { return s1 + s2 - sqrt(s1 * s1 + s2 * s2); }

// Bounded-blending displacement of s1, s2 inside the bounding solid s3 (0 outside it).
AM_MF_FN float amBoundedDisplacement(float s1, float s2, float s3, float a0, float a1, float a2, float a3) {
  float r1 = (s1 / a1) * (s1 / a1) + (s2 / a2) * (s2 / a2);
  float r2 = s3 > 0.0f ? (s3 / a3) * (s3 / a3) : 0.0f;
  float sum = r1 + r2;
  if (sum <= 0.0f) return 0.0f;
  float r = r1 / sum;
  if (r >= 1.0f) return 0.0f;
  float om = 1.0f - r;
  return a0 * om * om * om / (1.0f + r);
}

// Interpolation m = (1 - w) f1 + w f2.
AM_MF_FN float amMorphInterpolate(float f1, float f2, float w) { return (1.0f - w) * f1 + w * f2; }

// Space-time blending at morph time t (0: source, 1: target).
AM_MF_FN float amMorphSpaceTime(float f1, float f2, float t, float timeScale, float a0, float a1, float a2, float a3) {
  float tau = timeScale * t;
  float tau1 = timeScale * (t - 1.0f);
  float g1 = amRIntersection(f1, -tau);
  float g2 = amRIntersection(f2, tau1);
  float bound = amRIntersection(tau, -tau1);
  return amRUnion(g1, g2) + amBoundedDisplacement(g1, g2, bound, a0, a1, a2, a3);
}

#ifdef __cplusplus
}  // namespace animorph::morphfield
#endif
#undef AM_MF_FN

#endif  // ANIMORPH_MORPH_FIELD_H
