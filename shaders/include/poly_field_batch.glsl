// Batched value interpreter of a packed FieldProgram (FieldEvaluator::runChunk,
// values only) at 4 * AM_FIELD_V points per invocation (AM_FIELD_V vec4 per
// coordinate; the including shader defines it: 1 or 2). On lavapipe every
// buffer load inside a loop is a per-lane gather costing far more than the
// arithmetic, so a primitive's record is loaded once and applied to all the
// invocation's points; the convolution loop touches the point arrays only at
// constant indices (AM_EACH), so they stay in registers. Primitives whose bit is
// clear in the block mask contribute exactly 0 there (their bound does not reach
// the block), so skipping them is exact. Needs poly_field.glsl.
#ifndef AM_FIELD_V
#define AM_FIELD_V 2
#endif
#if AM_FIELD_V == 1
#define AM_EACH(M) M(0)
#elif AM_FIELD_V == 2
#define AM_EACH(M) M(0) M(1)
#else
#error "AM_FIELD_V must be 1 or 2 (16 and 32 points per invocation measured slower on lavapipe)"
#endif

struct PointsV {
  vec4 x[AM_FIELD_V], y[AM_FIELD_V], z[AM_FIELD_V];  // point 4 j + c is (x[j][c], y[j][c], z[j][c])
};

// Groups of 4 points along a grid line (AM_FIELD_LINES): along x (axis 0) point 4 j + c is
// (x[j][c], y[j], z[j]); along y (axis 1) it is (y[j], x[j][c], z[j]).
struct PointsL {
  vec4 x[AM_FIELD_V];
  float y[AM_FIELD_V], z[AM_FIELD_V];
  uint axis[AM_FIELD_V];
};

vec4 rUnion4(vec4 s1, vec4 s2) { return s1 + s2 + sqrt(s1 * s1 + s2 * s2); }
vec4 rIntersection4(vec4 s1, vec4 s2) { return s1 + s2 - sqrt(s1 * s1 + s2 * s2); }

vec4 boundedDisplacement4(vec4 s1, vec4 s2, vec4 s3, float a0, float a1, float a2, float a3) {
  return vec4(amBoundedDisplacement(s1.x, s2.x, s3.x, a0, a1, a2, a3),
              amBoundedDisplacement(s1.y, s2.y, s3.y, a0, a1, a2, a3),
              amBoundedDisplacement(s1.z, s2.z, s3.z, a0, a1, a2, a3),
              amBoundedDisplacement(s1.w, s2.w, s3.w, a0, a1, a2, a3));
}

vec4 spaceTime4(vec4 f1, vec4 f2) {
  vec4 r;
  for (int c = 0; c < 4; ++c)
    r[c] = amMorphSpaceTime(f1[c], f2[c], P.morph0.y, P.morph0.z, P.morph0.w, P.morph1.x, P.morph1.y, P.morph1.z);
  return r;
}

#define AM_LINES 0
#define AM_YZ vec4
#define AM_POINTS PointsV
#define AM_PROGRAM programV
#define AM_FIELD fieldV
#include "poly_field_program.glsl"
#undef AM_LINES
#undef AM_YZ
#undef AM_POINTS
#undef AM_PROGRAM
#undef AM_FIELD

#ifdef AM_FIELD_LINES
#define AM_LINES 1
#define AM_YZ float
#define AM_POINTS PointsL
#define AM_PROGRAM programL
#define AM_FIELD fieldL
#include "poly_field_program.glsl"
#undef AM_LINES
#undef AM_YZ
#undef AM_POINTS
#undef AM_PROGRAM
#undef AM_FIELD
#endif

// Sets point 4 j + c of w.
#define AM_SET_POINT(w, j, c, p) \
  {                              \
    vec3 q_ = (p);               \
    w.x[j][c] = q_.x;            \
    w.y[j][c] = q_.y;            \
    w.z[j][c] = q_.z;            \
  }
