#pragma once
// SSE2 forms of the affine SpaceMap operations on three-float lanes (lane 3 unused), for
// space_map.cpp and FieldProgram's primitive bounds: per lane the same float operations in the
// same order as the scalar code, so the results are bit for bit those of SpaceMap::toWorld and
// SpaceMap::worldBounds (and of glm::min / glm::max, Bounds::add). Internal to engine/core/field.
#if defined(__SSE2__)
#include <emmintrin.h>

#include <limits>

#include <glm/glm.hpp>

namespace animorph::simd {

// A vec3 in lanes 0-2; lane 3 is whatever follows it in memory (never stored, never tested): for
// vec3s followed by more of their object (a SpaceMap's matrix columns and origin).
inline __m128 lanes(const glm::vec3& v) { return _mm_loadu_ps(&v.x); }
// Any vec3, lane 3 zero.
inline __m128 load3(const glm::vec3& v) { return _mm_set_ps(0.0f, v.z, v.y, v.x); }
inline __m128 lanes(const glm::vec4& v) { return _mm_loadu_ps(&v.x); }
inline glm::vec3 vec3Of(__m128 v) {
  alignas(16) float f[4];
  _mm_store_ps(f, v);
  return glm::vec3(f[0], f[1], f[2]);
}
inline __m128 broadcast(__m128 v, int lane) {
  switch (lane) {
    case 0: return _mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 0, 0, 0));
    case 1: return _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 1, 1, 1));
    default: return _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 2, 2, 2));
  }
}
// glm::min(x, y) is (y < x) ? y : x per component, glm::max(x, y) is (x < y) ? y : x (signed
// zeros and NaNs included).
inline __m128 glmMin(__m128 x, __m128 y) { return _mm_min_ps(y, x); }
inline __m128 glmMax(__m128 x, __m128 y) { return _mm_max_ps(y, x); }
// Non-zero when some lane 0-2 of the comparison mask is set.
inline int any3(__m128 mask) { return _mm_movemask_ps(mask) & 7; }

// origin + ((c0 p.x + c1 p.y) + c2 p.z): an affine map's toWorld with forwardLinear's columns c0..c2.
inline __m128 affineToWorld(__m128 c0, __m128 c1, __m128 c2, __m128 origin, __m128 p) {
  const __m128 x = _mm_mul_ps(c0, broadcast(p, 0));
  const __m128 y = _mm_mul_ps(c1, broadcast(p, 1));
  const __m128 z = _mm_mul_ps(c2, broadcast(p, 2));
  return _mm_add_ps(origin, _mm_add_ps(_mm_add_ps(x, y), z));
}

// The box SpaceMap::worldBounds gives an affine map's image of the finite, non-empty child box
// [childMin, childMax]: per component origin + the sum of the smallest (largest) column products
// (rounded addition is monotonic in each operand). Valid when no bound comes out zero (whose sign
// depends on which corner gave it): returns false then, and worldBounds' corner loop decides.
inline bool affineWorldBox(__m128 c0, __m128 c1, __m128 c2, __m128 origin, __m128 childMin, __m128 childMax,
                           __m128& lo, __m128& hi) {
  // std::min(a, b) is b < a ? b : a, which is _mm_min_ps(b, a); std::max(a, b) is _mm_max_ps(b, a).
  const __m128 x0 = _mm_mul_ps(c0, broadcast(childMin, 0)), x1 = _mm_mul_ps(c0, broadcast(childMax, 0));
  const __m128 y0 = _mm_mul_ps(c1, broadcast(childMin, 1)), y1 = _mm_mul_ps(c1, broadcast(childMax, 1));
  const __m128 z0 = _mm_mul_ps(c2, broadcast(childMin, 2)), z1 = _mm_mul_ps(c2, broadcast(childMax, 2));
  lo = _mm_add_ps(origin, _mm_add_ps(_mm_add_ps(_mm_min_ps(x1, x0), _mm_min_ps(y1, y0)), _mm_min_ps(z1, z0)));
  hi = _mm_add_ps(origin, _mm_add_ps(_mm_add_ps(_mm_max_ps(x1, x0), _mm_max_ps(y1, y0)), _mm_max_ps(z1, z0)));
  const __m128 zero = _mm_setzero_ps();
  return any3(_mm_or_ps(_mm_cmpeq_ps(lo, zero), _mm_cmpeq_ps(hi, zero))) == 0;
}

// Bounds{} with lo then hi added (Bounds::add), as [boxMin, boxMax].
inline void boxOfTwo(__m128 lo, __m128 hi, __m128& boxMin, __m128& boxMax) {
  boxMin = glmMin(glmMin(_mm_set1_ps(std::numeric_limits<float>::max()), lo), hi);
  boxMax = glmMax(glmMax(_mm_set1_ps(-std::numeric_limits<float>::max()), lo), hi);
}

// All of lanes 0-2 of a and b finite.
inline bool finite3(__m128 a, __m128 b) {
  const __m128 zero = _mm_setzero_ps();
  const __m128 ok = _mm_and_ps(_mm_cmpeq_ps(_mm_sub_ps(a, a), zero), _mm_cmpeq_ps(_mm_sub_ps(b, b), zero));
  return (_mm_movemask_ps(ok) & 7) == 7;
}

}  // namespace animorph::simd
#endif
