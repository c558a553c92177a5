// Batched primitive kernels: the hot loops of field evaluation. Primitives
// outside, points inside, so the point loop vectorises (structure of arrays).
// This file is compiled with -fno-math-errno (engine/core/CMakeLists.txt) so
// sqrt and division vectorise, and cloned for AVX-512 / AVX2 / baseline with
// run-time dispatch. atan2 is a polynomial (Cephes atanf, ~1 ulp).
#include <algorithm>
#include <cmath>
#include <vector>

#include "field/field_program.h"
#include "field/potential.h"
#include "field/skeleton.h"
#include "field/spline_curve.h"
#include "field/field_program_detail.h"

namespace animorph {

namespace {

// atan2(y, x) for y > 0, branch-free (selects) so it vectorises.
inline float atan2PositiveY(float y, float x) {
  float ax = x < 0.0f ? -x : x;
  float mn = ax < y ? ax : y;
  float mx = ax < y ? y : ax;
  bool big = mn > 0.41421356237f * mx;  // tan(pi/8)
  float num = big ? mn - mx : mn;
  float den = big ? mn + mx : mx;
  float t = num / den;
  float z = t * t;
  float r = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z * t + t;
  r += big ? 0.78539816340f : 0.0f;
  r = y > ax ? 1.57079632679f - r : r;
  r = x < 0.0f ? 3.14159265359f - r : r;
  return r;
}

ANIMORPH_KERNEL
void convolutionValues(const float* __restrict bxs, const float* __restrict bys, const float* __restrict bzs,
                       const float* __restrict axs, const float* __restrict ays, const float* __restrict azs,
                       const float* __restrict lens, const float* __restrict ws, const float* __restrict ss,
                       const float* __restrict cuts, const uint32_t* __restrict idx, int count,
                       const float* __restrict x, const float* __restrict y, const float* __restrict z, int n,
                       float* __restrict f) {
  for (int k = 0; k < count; ++k) {
    const uint32_t i = idx[k];
    const float bx = bxs[i], by = bys[i], bz = bzs[i], ax = axs[i], ay = ays[i], az = azs[i];
    const float l = lens[i], halfW = 0.5f * ws[i], S = ss[i], S2 = S * S, invS = 1.0f / S, cut2 = cuts[i];
    const float Sl = S * l, l2 = l * l;
    for (int j = 0; j < n; ++j) {
      float dx = x[j] - bx, dy = y[j] - by, dz = z[j] - bz;
      float dd = dx * dx + dy * dy + dz * dz;
      float u = dx * ax + dy * ay + dz * az;
      float perp2 = dd - u * u;
      perp2 = perp2 > 0.0f ? perp2 : 0.0f;
      float P = 1.0f + S2 * perp2;
      float D = 1.0f + S2 * dd;
      float lu = l - u;
      float e2 = dd - 2.0f * l * u + l2;
      float Q = 1.0f + S2 * e2;
      float invP = 1.0f / P;
      float p = std::sqrt(P);
      float A = atan2PositiveY(Sl * p, P - S2 * u * lu);
      float invDQ = 1.0f / (D * Q);
      float F = invP * ((u * Q + lu * D) * invDQ + A * p * invP * invS);
      float seg2 = u < 0.0f ? dd : (u > l ? e2 : perp2);
      f[j] += seg2 <= cut2 ? halfW * F : 0.0f;
    }
  }
}

ANIMORPH_KERNEL
void convolutionGradients(const float* __restrict bxs, const float* __restrict bys, const float* __restrict bzs,
                          const float* __restrict axs, const float* __restrict ays, const float* __restrict azs,
                          const float* __restrict lens, const float* __restrict ws, const float* __restrict ss,
                          const float* __restrict cuts, const uint32_t* __restrict idx, int count,
                          const float* __restrict x, const float* __restrict y, const float* __restrict z, int n,
                          float* __restrict f, float* __restrict gx, float* __restrict gy, float* __restrict gz) {
  for (int k = 0; k < count; ++k) {
    const uint32_t i = idx[k];
    const float bx = bxs[i], by = bys[i], bz = bzs[i], ax = axs[i], ay = ays[i], az = azs[i];
    const float l = lens[i], w = ws[i], S = ss[i], S2 = S * S, invS = 1.0f / S, cut2 = cuts[i];
    const float Sl = S * l, l2 = l * l;
    for (int j = 0; j < n; ++j) {
      float dx = x[j] - bx, dy = y[j] - by, dz = z[j] - bz;
      float dd = dx * dx + dy * dy + dz * dz;
      float u = dx * ax + dy * ay + dz * az;
      float perp2 = dd - u * u;
      perp2 = perp2 > 0.0f ? perp2 : 0.0f;
      float P = 1.0f + S2 * perp2;
      float D = 1.0f + S2 * dd;
      float lu = l - u;
      float e2 = dd - 2.0f * l * u + l2;
      float Q = 1.0f + S2 * e2;
      float invP = 1.0f / P;
      float p = std::sqrt(P);
      float A = atan2PositiveY(Sl * p, P - S2 * u * lu);
      float invDQ = 1.0f / (D * Q);
      float invD = Q * invDQ, invQ = D * invDQ;
      float F = 0.5f * invP * ((u * Q + lu * D) * invDQ + A * p * invP * invS);
      float J0 = 0.25f * invP * (lu * invQ * invQ + u * invD * invD + 3.0f * F);
      float radial = -4.0f * S2 * J0;
      float axial = invD * invD - invQ * invQ;
      float seg2 = u < 0.0f ? dd : (u > l ? e2 : perp2);
      float m = seg2 <= cut2 ? w : 0.0f;
      float rx = dx - u * ax, ry = dy - u * ay, rz = dz - u * az;
      f[j] += m * F;
      gx[j] += m * (radial * rx + axial * ax);
      gy[j] += m * (radial * ry + axial * ay);
      gz[j] += m * (radial * rz + axial * az);
    }
  }
}

// Per-primitive intervals of w F over the ball (c, rho): the kernel is
// decreasing in distance, so each eighth of a segment contributes between
// length * h(farthest) and length * h(nearest). Primitives are the SIMD lanes.
ANIMORPH_KERNEL
void convolutionIntervals(const float* __restrict bxs, const float* __restrict bys, const float* __restrict bzs,
                          const float* __restrict axs, const float* __restrict ays, const float* __restrict azs,
                          const float* __restrict lens, const float* __restrict ws, const float* __restrict ss,
                          const float* __restrict cuts, const uint32_t* __restrict idx, int count, float cx, float cy,
                          float cz, float rho, float* __restrict lo, float* __restrict hi) {
  for (int k = 0; k < count; ++k) {
    const uint32_t i = idx[k];
    const float l = lens[i], S2 = ss[i] * ss[i], cut2 = cuts[i];
    float dx = cx - bxs[i], dy = cy - bys[i], dz = cz - bzs[i];
    float uc = dx * axs[i] + dy * ays[i] + dz * azs[i];
    float perp2 = dx * dx + dy * dy + dz * dz - uc * uc;
    perp2 = perp2 > 0.0f ? perp2 : 0.0f;
    float along = uc < 0.0f ? -uc : (uc > l ? uc - l : 0.0f);
    float dseg = std::sqrt(perp2 + along * along);
    const float ds = l * 0.125f;
    float sumLo = 0.0f, sumHi = 0.0f;
#pragma GCC unroll 8
    for (int q = 0; q < 8; ++q) {
      float s0 = ds * float(q), s1 = s0 + ds;
      float nearD = uc < s0 ? s0 - uc : (uc > s1 ? uc - s1 : 0.0f);
      float a0 = s0 - uc, a1 = s1 - uc;
      a0 = a0 < 0.0f ? -a0 : a0;
      a1 = a1 < 0.0f ? -a1 : a1;
      float farD = a0 > a1 ? a0 : a1;
      float rmin = std::sqrt(perp2 + nearD * nearD) - rho;
      rmin = rmin > 0.0f ? rmin : 0.0f;
      float rmax = std::sqrt(perp2 + farD * farD) + rho;
      float kmax = 1.0f / (1.0f + S2 * rmin * rmin);
      float kmin = 1.0f / (1.0f + S2 * rmax * rmax);  // 0 for an infinite ball
      sumHi += kmax * kmax;
      sumLo += kmin * kmin;
    }
    float wds = ws[i] * ds;
    float dOut = dseg - rho, dIn = dseg + rho;
    bool none = dOut * dOut > cut2 && dOut > 0.0f;
    bool all = dIn * dIn <= cut2;
    // Widened by a few ulps: the values themselves are computed in float.
    lo[k] = all ? wds * sumLo * 0.9999f : 0.0f;
    hi[k] = none ? 0.0f : wds * sumHi * 1.0001f;
  }
}

template <bool kMax>
inline void accumulate(float* f, float* gx, float* gy, float* gz, int j, float v, float vx, float vy, float vz) {
  if constexpr (kMax) {
    if (v > f[j]) {
      f[j] = v;
      if (gx) {
        gx[j] = vx;
        gy[j] = vy;
        gz[j] = vz;
      }
    }
  } else {
    f[j] += v;
    if (gx) {
      gx[j] += vx;
      gy[j] += vy;
      gz[j] += vz;
    }
  }
}

// Squared distance between the segment (a, b) and the box [lo, hi], or less: a lower bound from
// the box of the segment (exact when the segment is a point or axis-aligned).
inline float segmentBoxGap2(const glm::vec3& a, const glm::vec3& b, const glm::vec3& lo, const glm::vec3& hi) {
  glm::vec3 gap = glm::max(glm::vec3(0.0f), glm::max(lo - glm::max(a, b), glm::min(a, b) - hi));
  return glm::dot(gap, gap);
}

template <bool kMax>
void skeletalLoop(const FieldProgram& prog, const uint32_t* idx, int count, const float* x, const float* y,
                  const float* z, int n, const glm::vec3& boxLo, const glm::vec3& boxHi, float* f, float* gx,
                  float* gy, float* gz) {
  thread_local std::vector<float> gaps;
  thread_local std::vector<int> insideList;
  if (gaps.size() < size_t(n)) {
    gaps.resize(size_t(n));
    insideList.resize(size_t(n));
  }
  float* __restrict gapBuffer = gaps.data();
  int* __restrict insideBuffer = insideList.data();
  // A primitive that reaches none of the points adds nothing (sum: + 0; max: the values start at
  // 0 and a point it does not reach would get 0), so whole primitives are skipped against the
  // points' box: polygonisers pass compact runs of points, and most of a block's primitives reach
  // only part of it.
  for (int k = 0; k < count; ++k) {
    const SkeletalReach& bound = prog.skeletalReach[idx[k]];
    const glm::vec3 ca = bound.a, cb = bound.b;
    const float reach = bound.reach;
    if (segmentBoxGap2(ca, cb, boxLo, boxHi) >= reach * reach) continue;
    const SkeletalPrimitive& p = prog.skeletal[idx[k]];
    Skeleton s = p.skeleton;
    if (s.kind == SkeletonKind::Curve) s.curve = prog.curvePoints.data() + p.curveFirst;
    const float R = p.radius, I = p.intensity, K = p.stiffness;
    // Cheap rejection per point: the bound's capsule, in this primitive's own space, over all the
    // points first (a loop the compiler vectorises), then the points inside it. A rejected point
    // would add 0 (the sums start at +0 and never become -0; the maxima start at 0), so it is
    // left out.
    const glm::vec3 ab = cb - ca;
    const float l2 = glm::dot(ab, ab);
    const float reach2 = reach * reach;
    int inside = 0;
    if (l2 > 0.0f) {
      for (int j = 0; j < n; ++j) {
        float dx = x[j] - ca.x, dy = y[j] - ca.y, dz = z[j] - ca.z;
        float t = std::clamp((dx * ab.x + dy * ab.y + dz * ab.z) / l2, 0.0f, 1.0f);
        float ex = x[j] - (ca.x + t * ab.x), ey = y[j] - (ca.y + t * ab.y), ez = z[j] - (ca.z + t * ab.z);
        gapBuffer[j] = ex * ex + ey * ey + ez * ez;
      }
    } else {
      for (int j = 0; j < n; ++j) {
        float ex = x[j] - ca.x, ey = y[j] - ca.y, ez = z[j] - ca.z;
        gapBuffer[j] = ex * ex + ey * ey + ez * ez;
      }
    }
    // Branch-free compaction: which points pass is data-dependent (a branch per point mispredicts
    // often); each index is written and the count advances only when it passes.
    for (int j = 0; j < n; ++j) {
      insideBuffer[inside] = j;
      inside += !(gapBuffer[j] >= reach2) ? 1 : 0;
    }
    for (int w = 0; w < inside; ++w) {
      const int j = insideBuffer[w];
      glm::vec3 q(x[j], y[j], z[j]);
      glm::vec3 c;
      switch (s.kind) {
        case SkeletonKind::Point: c = s.p0; break;
        case SkeletonKind::Segment: c = closestOnSegment(q, s.p0, s.p1); break;
        default: c = closestOnSkeleton(s, q);
      }
      glm::vec3 d = q - c;
      float gf;
      float v = skeletalPotential(glm::dot(d, d), R, I, K, gf);
      accumulate<kMax>(f, gx, gy, gz, j, v, gf * d.x, gf * d.y, gf * d.z);
    }
  }
}

template <bool kMax>
void capsuleLoop(const std::vector<CapsulePrimitive>& caps, float T, const uint32_t* idx, int count, const float* x,
                 const float* y, const float* z, int n, float* f, float* gx, float* gy, float* gz) {
  for (int k = 0; k < count; ++k) {
    const CapsulePrimitive& c = caps[idx[k]];
    if (c.radius <= 0.0f) {
      for (int j = 0; j < n; ++j) accumulate<kMax>(f, gx, gy, gz, j, 0.0f, 0.0f, 0.0f, 0.0f);
      continue;
    }
    const float invR = 1.0f / c.radius;
    for (int j = 0; j < n; ++j) {
      glm::vec3 q(x[j], y[j], z[j]);
      glm::vec3 d = q - closestOnSegment(q, c.a, c.b);
      float dist = glm::length(d);
      float v = T * (2.0f - dist * invR);
      if (v <= 0.0f) {
        accumulate<kMax>(f, gx, gy, gz, j, 0.0f, 0.0f, 0.0f, 0.0f);
        continue;
      }
      float gfac = dist > 0.0f ? -T * invR / dist : 0.0f;
      accumulate<kMax>(f, gx, gy, gz, j, v, gfac * d.x, gfac * d.y, gfac * d.z);
    }
  }
}

}  // namespace

void convolutionKernel(const ConvolutionData& c, const uint32_t* idx, int count, const float* x, const float* y,
                       const float* z, int n, float* f, float* gx, float* gy, float* gz) {
  if (gx)
    convolutionGradients(c.bx.data(), c.by.data(), c.bz.data(), c.ax.data(), c.ay.data(), c.az.data(),
                         c.length.data(), c.weight.data(), c.sharpness.data(), c.cut2.data(), idx, count, x, y, z, n,
                         f, gx, gy, gz);
  else
    convolutionValues(c.bx.data(), c.by.data(), c.bz.data(), c.ax.data(), c.ay.data(), c.az.data(), c.length.data(),
                      c.weight.data(), c.sharpness.data(), c.cut2.data(), idx, count, x, y, z, n, f);
}

void convolutionIntervalKernel(const ConvolutionData& c, const uint32_t* idx, int count, const glm::vec3& centre,
                               float radius, float* lo, float* hi) {
  convolutionIntervals(c.bx.data(), c.by.data(), c.bz.data(), c.ax.data(), c.ay.data(), c.az.data(), c.length.data(),
                       c.weight.data(), c.sharpness.data(), c.cut2.data(), idx, count, centre.x, centre.y, centre.z,
                       radius, lo, hi);
}

void skeletalKernel(const FieldProgram& prog, const uint32_t* idx, int count, bool combineMax, const float* x,
                    const float* y, const float* z, int n, const glm::vec3& boxLo, const glm::vec3& boxHi, float* f,
                    float* gx, float* gy, float* gz) {
  if (combineMax) skeletalLoop<true>(prog, idx, count, x, y, z, n, boxLo, boxHi, f, gx, gy, gz);
  else skeletalLoop<false>(prog, idx, count, x, y, z, n, boxLo, boxHi, f, gx, gy, gz);
}

void capsuleKernel(const std::vector<CapsulePrimitive>& caps, float threshold, const uint32_t* idx, int count,
                   bool combineMax, const float* x, const float* y, const float* z, int n, float* f, float* gx,
                   float* gy, float* gz) {
  if (combineMax) capsuleLoop<true>(caps, threshold, idx, count, x, y, z, n, f, gx, gy, gz);
  else capsuleLoop<false>(caps, threshold, idx, count, x, y, z, n, f, gx, gy, gz);
}

}  // namespace animorph
