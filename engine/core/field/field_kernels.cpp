// Batched primitive kernels: the hot loops of field evaluation. Primitives
// outside, points inside, so the point loop vectorises (structure of arrays).
// This file is compiled with -fno-math-errno (engine/core/CMakeLists.txt) so
// sqrt and division vectorise, and cloned for AVX-512 / AVX2 / baseline with
// run-time dispatch. atan2 is a polynomial (Cephes atanf, ~1 ulp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/field/field_program.h"
#include "core/field/potential.h"
#include "core/field/skeleton.h"
#include "core/field/spline_curve.h"
#include "core/field/field_program_detail.h"

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

// A union (max) of triangle primitives sharing radius R, intensity I > 0 and an integer stiffness
// (the wings' Coons patches): g is then non-increasing in the squared distance d2 as computed in
// float (d2 / R^2, 1 - x and the multiply chain are each monotone), so a triangle whose distance
// to a point is at least that of the point's best triangle so far gives a value <= the kept one
// and cannot change it. Triangles are bounded by the disc (centroid, reach - R) in their plane,
// with a margin far above float rounding, and visited nearest the points first: the largest value
// does not depend on the order. With gradients, a second pass in the program's order finds the
// first triangle reaching each point's largest value (the plain loop keeps its gradient), among
// the triangles that may reach it. Every value and gradient is the plain loop's. False: not such
// a union.
struct TriangleUnion {
  // The triangles reaching the points' box, structure of arrays: centroid, unit normal (0 for a
  // degenerate triangle), radius of the disc about the centroid holding it, squared reach.
  std::vector<float> cx, cy, cz, nx, ny, nz, ball, reach2;
  std::vector<int> k;                  // index in the op's list
  std::vector<float> near;             // per triangle: lower bound of its distance to one group
  struct Candidate {
    float near;
    int t;
  };
  std::vector<Candidate> list, sorted;  // one group's triangles, in visiting order
  std::vector<float> limit, slack;     // per point: distance a triangle must beat; test
  std::vector<int> pass;               // points passing the test
  float R = 0.0f, I = 0.0f, K = 0.0f, margin = 0.0f;
};

constexpr int kPointGroup = 16;  // points per group: a run's points are numbered along the grid

// One pass over the points, a group of consecutive ones at a time: the group's triangles that may
// come nearer than the largest of its points' limits (by the disc bounds, against the group's
// box), roughly nearest first when `nearFirst`, else in the program's order; each one still
// nearer than that largest limit is tested against the group's points by the same bound, then
// evaluated where it may beat the limit: `visit(j, d, d2, v, gf)` decides and returns true when
// it lowered limit[j].
template <typename Visit>
void trianglePass(TriangleUnion& u, const FieldProgram& prog, const uint32_t* idx, const float* x, const float* y,
                  const float* z, int n, bool nearFirst, Visit visit) {
  const int count = int(u.k.size());
  float* __restrict limit = u.limit.data();
  float* __restrict slackBuffer = u.slack.data();
  float* __restrict nearBuffer = u.near.data();
  int* __restrict pass = u.pass.data();
  const float* __restrict cxs = u.cx.data();
  const float* __restrict cys = u.cy.data();
  const float* __restrict czs = u.cz.data();
  const float* __restrict nxs = u.nx.data();
  const float* __restrict nys = u.ny.data();
  const float* __restrict nzs = u.nz.data();
  const float* __restrict balls = u.ball.data();
  const float R = u.R, I = u.I, K = u.K, margin = u.margin;
  for (int j0 = 0; j0 < n; j0 += kPointGroup) {
    const int j1 = std::min(n, j0 + kPointGroup);
    float groupLimit = 0.0f;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (int j = j0; j < j1; ++j) {
      groupLimit = std::max(groupLimit, limit[j]);
      lo = glm::min(lo, glm::vec3(x[j], y[j], z[j]));
      hi = glm::max(hi, glm::vec3(x[j], y[j], z[j]));
    }
    if (!(groupLimit > 0.0f)) continue;
    const float ox = 0.5f * (lo.x + hi.x), oy = 0.5f * (lo.y + hi.y), oz = 0.5f * (lo.z + hi.z);
    const float hx = 0.5f * (hi.x - lo.x), hy = 0.5f * (hi.y - lo.y), hz = 0.5f * (hi.z - lo.z);
    // Distance from the group's box to each triangle, at least: to its ball and to its plane
    // (max(a, 0) and max(a, b) written with |.| so the loop vectorises; the margin covers their
    // rounding).
    for (int t = 0; t < count; ++t) {
      float dx = std::fabs(ox - cxs[t]) - hx, dy = std::fabs(oy - cys[t]) - hy, dz = std::fabs(oz - czs[t]) - hz;
      dx = 0.5f * (dx + std::fabs(dx));
      dy = 0.5f * (dy + std::fabs(dy));
      dz = 0.5f * (dz + std::fabs(dz));
      float toBall = std::sqrt(dx * dx + dy * dy + dz * dz) - balls[t];
      float toPlane = std::fabs((ox - cxs[t]) * nxs[t] + (oy - cys[t]) * nys[t] + (oz - czs[t]) * nzs[t]) -
                      (hx * std::fabs(nxs[t]) + hy * std::fabs(nys[t]) + hz * std::fabs(nzs[t]));
      nearBuffer[t] = 0.5f * (toBall + toPlane + std::fabs(toBall - toPlane));
    }
    u.list.clear();
    float nearest = INFINITY;
    for (int t = 0; t < count; ++t)
      if (nearBuffer[t] - margin < groupLimit) {
        u.list.push_back({nearBuffer[t], t});
        nearest = std::min(nearest, nearBuffer[t]);
      }
    if (nearFirst && u.list.size() > 1) {
      // Nearest first, roughly: a counting sort into bins of the bound (a full sort costs more
      // than the order saves).
      constexpr int kBins = 16;
      int start[kBins + 1] = {};
      const float scale = float(kBins) / std::max(groupLimit + margin - nearest, 1e-30f);
      auto bin = [&](float near) { return std::clamp(int((near - nearest) * scale), 0, kBins - 1); };
      for (const TriangleUnion::Candidate& c : u.list) ++start[bin(c.near) + 1];
      for (int b = 0; b < kBins; ++b) start[b + 1] += start[b];
      u.sorted.resize(u.list.size());
      for (const TriangleUnion::Candidate& c : u.list) u.sorted[size_t(start[bin(c.near)]++)] = c;
      u.list.swap(u.sorted);
    }
    for (const TriangleUnion::Candidate& cand : u.list) {
      if (cand.near - margin >= groupLimit) continue;
      const int t = cand.t;
      const float cx = cxs[t], cy = cys[t], cz = czs[t], nx = nxs[t], ny = nys[t], nz = nzs[t], ball = balls[t];
      const float reach2 = u.reach2[size_t(t)];
      // Per point, negative when the triangle may beat its limit: inside the plain loop's own
      // test (the same float expression: the same points pass it) and the disc nearer than the
      // limit. A loop the compiler vectorises, then a branch-free compaction.
      for (int j = j0; j < j1; ++j) {
        float ex = x[j] - cx, ey = y[j] - cy, ez = z[j] - cz;
        float gap2 = ex * ex + ey * ey + ez * ez;
        float h = ex * nx + ey * ny + ez * nz;
        float s2 = std::max(gap2 - h * h, 0.0f);
        float sd = std::sqrt(s2) - ball;
        float side = 0.5f * (sd + std::fabs(sd));  // max(sd, 0), in a form that vectorises
        float reachJ = limit[j] + margin;
        float slack = h * h + side * side - reachJ * reachJ;
        slackBuffer[j] = std::max(slack, gap2 - reach2);  // gap2 - reach2 < 0 exactly when gap2 < reach2
      }
      int inside = 0;
      for (int j = j0; j < j1; ++j) {
        pass[inside] = j;
        inside += slackBuffer[j] < 0.0f ? 1 : 0;
      }
      if (inside == 0) continue;
      const Skeleton& s = prog.skeletal[idx[u.k[size_t(t)]]].skeleton;
      bool changed = false;
      for (int w = 0; w < inside; ++w) {
        const int j = pass[w];
        glm::vec3 q(x[j], y[j], z[j]);
        glm::vec3 d = q - closestOnTriangle(q, s.p0, s.p1, s.p2);
        float d2 = glm::dot(d, d);
        float gf;
        float v = skeletalPotential(d2, R, I, K, gf);
        changed |= visit(j, d, d2, v, gf);
      }
      if (changed) {
        groupLimit = 0.0f;
        for (int j = j0; j < j1; ++j) groupLimit = std::max(groupLimit, limit[j]);
      }
    }
  }
}

bool triangleUnionLoop(const FieldProgram& prog, const uint32_t* idx, int count, const float* x, const float* y,
                       const float* z, int n, const glm::vec3& boxLo, const glm::vec3& boxHi, float* f, float* gx,
                       float* gy, float* gz) {
  thread_local TriangleUnion u;
  for (auto* v : {&u.cx, &u.cy, &u.cz, &u.nx, &u.ny, &u.nz, &u.ball, &u.reach2}) v->clear();
  u.k.clear();
  float ballMax = 0.0f;
  for (int k = 0; k < count; ++k) {
    const SkeletalReach& bound = prog.skeletalReach[idx[k]];
    const float gap2 = segmentBoxGap2(bound.a, bound.b, boxLo, boxHi);
    if (!std::isfinite(gap2) || bound.a != bound.b) return false;
    if (gap2 >= bound.reach * bound.reach) continue;
    const SkeletalPrimitive& p = prog.skeletal[idx[k]];
    if (p.skeleton.kind != SkeletonKind::Triangle) return false;
    if (u.k.empty()) {
      u.R = p.radius;
      u.I = p.intensity;
      u.K = p.stiffness;
      if (!(u.R > 0.0f) || !(u.I > 0.0f) || !(u.K >= 0.0f && u.K <= 8.0f && float(int(u.K)) == u.K)) return false;
    } else if (p.radius != u.R || p.intensity != u.I || p.stiffness != u.K) {
      return false;
    }
    const Skeleton& s = p.skeleton;
    glm::vec3 nrm = glm::cross(s.p1 - s.p0, s.p2 - s.p0);
    const float nl = glm::length(nrm);
    nrm = nl > 0.0f && std::isfinite(nl) ? nrm / nl : glm::vec3(0.0f);
    const float ball = std::max(0.0f, bound.reach - u.R);
    ballMax = std::max(ballMax, ball);
    u.cx.push_back(bound.a.x);
    u.cy.push_back(bound.a.y);
    u.cz.push_back(bound.a.z);
    u.nx.push_back(nrm.x);
    u.ny.push_back(nrm.y);
    u.nz.push_back(nrm.z);
    u.ball.push_back(ball);
    u.reach2.push_back(bound.reach * bound.reach);
    u.k.push_back(k);
  }
  if (u.k.size() < 2) return false;
  u.near.resize(u.k.size());
  const float R = u.R, I = u.I, K = u.K;
  // Float rounding of the distances is ~1e-7 of the coordinates' size; the margin is 100 times that.
  const float extent = std::max({std::abs(boxLo.x), std::abs(boxLo.y), std::abs(boxLo.z), std::abs(boxHi.x),
                                 std::abs(boxHi.y), std::abs(boxHi.z)});
  u.margin = 1e-5f * (extent + R + ballMax);
  if (u.limit.size() < size_t(n)) {
    u.limit.resize(size_t(n));
    u.slack.resize(size_t(n));
    u.pass.resize(size_t(n));
  }
  // Values: the limit is the distance of the best triangle so far (R: none reaches the point).
  float* limit = u.limit.data();
  for (int j = 0; j < n; ++j) limit[j] = R;
  trianglePass(u, prog, idx, x, y, z, n, true, [&](int j, const glm::vec3&, float d2, float v, float) {
    if (!(v > f[j])) return false;
    f[j] = v;
    limit[j] = std::sqrt(d2);
    return true;
  });
  if (!gx) return true;
  // Gradients: the first triangle, in the program's order, whose value is the point's largest.
  // Its squared distance is at most the largest float d2 with g(d2) = f (found by bisection on
  // the bits: g is monotone), so the others lie beyond that distance plus the margin.
  for (int j = 0; j < n; ++j) {
    if (!(f[j] > 0.0f)) {
      limit[j] = -u.margin;  // no triangle reaches the point: its gradient stays 0 (no test passes)
      continue;
    }
    float gf;
    auto reaches = [&](uint32_t bits) {
      float d2;
      std::memcpy(&d2, &bits, 4);
      return skeletalPotential(d2, R, I, K, gf) >= f[j];
    };
    uint32_t lo, hi;
    const float loD2 = limit[j] * limit[j] * 0.9999995f, r2 = R * R;
    std::memcpy(&lo, &loD2, 4);
    std::memcpy(&hi, &r2, 4);
    if (!reaches(lo)) {
      lo = 0;  // g(0) = I >= f
    } else {
      // The plateau is mostly a few ulps wide: gallop up from the best d2, then bisect.
      for (uint32_t step = 1; lo + step < hi && reaches(lo + step); step *= 2) lo += step;
      for (uint32_t step = 1; lo + step < hi; step *= 2)
        if (!reaches(lo + step)) {
          hi = lo + step;
          break;
        }
    }
    while (hi - lo > 1) {  // g(lo) >= f > g(hi): non-negative floats order as their bits
      const uint32_t mid = lo + (hi - lo) / 2;
      (reaches(mid) ? lo : hi) = mid;
    }
    float plateau;
    std::memcpy(&plateau, &lo, 4);
    limit[j] = std::sqrt(plateau) * 1.0001f;
  }
  trianglePass(u, prog, idx, x, y, z, n, false, [&](int j, const glm::vec3& d, float, float v, float gf) {
    if (v != f[j]) return false;
    gx[j] = gf * d.x;
    gy[j] = gf * d.y;
    gz[j] = gf * d.z;
    limit[j] = -u.margin;  // found: limit + margin is 0, and no later triangle passes the test
    return true;
  });
  return true;
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
  if (combineMax) {
    if (triangleUnionLoop(prog, idx, count, x, y, z, n, boxLo, boxHi, f, gx, gy, gz)) return;
    skeletalLoop<true>(prog, idx, count, x, y, z, n, boxLo, boxHi, f, gx, gy, gz);
  }
  else skeletalLoop<false>(prog, idx, count, x, y, z, n, boxLo, boxHi, f, gx, gy, gz);
}

void capsuleKernel(const std::vector<CapsulePrimitive>& caps, float threshold, const uint32_t* idx, int count,
                   bool combineMax, const float* x, const float* y, const float* z, int n, float* f, float* gx,
                   float* gy, float* gz) {
  if (combineMax) capsuleLoop<true>(caps, threshold, idx, count, x, y, z, n, f, gx, gy, gz);
  else capsuleLoop<false>(caps, threshold, idx, count, x, y, z, n, f, gx, gy, gz);
}

}  // namespace animorph
