#include "core/field/surface_color.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/field/field_program_detail.h"
#include "core/field/operators.h"

namespace animorph {

namespace {

constexpr int kRun = SurfaceColorEvaluator::kRun;  // points evaluated together (one specialised program per run)

// One run's operand stack: entry s holds kRun values, then kRun each of r, g, b; the map levels'
// points; a scratch row for one primitive's contribution and one for the weights.
using RunScratch = SurfaceColorEvaluator::RunScratch;

const glm::vec3& clayLinear() {
  static const glm::vec3 clay = srgbToLinear(kClayColorSrgb);
  return clay;
}

// The colour provenance specialise leaves in an op of an ActiveProgram (its subtreeBegin, see
// field_program_specialise.cpp): the rule (0 none; 1 everywhere; 2 where every operand's weight is
// 0; 3 where its value is <= 0) and the empty colour it gives (clay without one).
uint32_t colorRule(const FieldOp& op) { return op.subtreeBegin >> 30; }
glm::vec3 ruleColor(const ColorProgram& CP, const FieldOp& op) {
  const uint32_t ref = op.subtreeBegin & 0x3fffffffu;
  return ref > 0 && ref - 1 < CP.emptyColor.size() ? CP.emptyColor[ref - 1] : clayLinear();
}

// The colour of a Const op: a constant of the program is clay; one standing for a subtree that
// specialisation dropped has that subtree's colour where none of its primitives contributes.
glm::vec3 constColor(const ColorProgram& CP, const FieldOp& op) { return ruleColor(CP, op); }

// The colour of a Prims op where none of its primitives contributes: its first primitive's (in the
// whole program, whichever of them a specialised op still holds).
glm::vec3 primsFallback(const ColorProgram& CP, const FieldOp& op) {
  return op.primBegin < CP.primColor.size() ? CP.primColor[op.primBegin] : clayLinear();
}

void boxOf(const float* x, const float* y, const float* z, int n, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::vec3(INFINITY);
  hi = glm::vec3(-INFINITY);
  for (int i = 0; i < n; ++i) {
    lo = glm::min(lo, glm::vec3(x[i], y[i], z[i]));
    hi = glm::max(hi, glm::vec3(x[i], y[i], z[i]));
  }
}

// Sets entry s's colour to c at every point.
void fillColor(RunScratch& S, int s, int n, const glm::vec3& c) {
  for (int k = 0; k < 3; ++k) std::fill(S.C(s, k), S.C(s, k) + n, c[k]);
}

// Entry s's colour is c at every point (its r, g, b rows are left unwritten).
void setUniform(RunScratch& S, int s, const glm::vec3& c) {
  S.uni[s] = 1;
  S.uc[s] = c;
}

// Sets entry s's gradient to 0 at every point (in a walk with gradients).
void zeroGradient(RunScratch& S, int s, int n) {
  if (!S.grad) return;
  for (int a = 0; a < 3; ++a) std::fill(S.G(s, a), S.G(s, a) + n, 0.0f);
}

// Entry s's rows written: its value (and gradient) rows where it is +0 everywhere, its colour rows
// where it has one colour (the per-point rules read them).
void materialise(RunScratch& S, int s, int n) {
  if (S.zero[s]) {
    std::fill(S.V(s), S.V(s) + n, 0.0f);
    zeroGradient(S, s, n);
  }
  if (S.uni[s]) fillColor(S, s, n, S.uc[s]);
  S.zero[s] = S.uni[s] = 0;
}

// The field of primitives idx[0, count) at the points into f (summed, or their max with 0), and
// its gradient into gx, gy, gz when gx is not null: from zeros, as the field evaluator's Prims op.
void contribution(const FieldProgram& P, PrimClass cls, const uint32_t* idx, int count, bool combineMax,
                  const float* x, const float* y, const float* z, int n, const glm::vec3& lo, const glm::vec3& hi,
                  float* f, float* gx = nullptr, float* gy = nullptr, float* gz = nullptr) {
  std::fill(f, f + n, 0.0f);
  if (gx)
    for (float* g : {gx, gy, gz}) std::fill(g, g + n, 0.0f);
  switch (cls) {
    case PrimClass::Skeletal: skeletalKernel(P, idx, count, combineMax, x, y, z, n, lo, hi, f, gx, gy, gz); break;
    case PrimClass::Convolution: convolutionKernel(P.convolution, idx, count, x, y, z, n, f, gx, gy, gz); break;
    case PrimClass::Capsule:
      capsuleKernel(P.capsules, P.threshold, idx, count, combineMax, x, y, z, n, f, gx, gy, gz);
      break;
  }
}

// True when every primitive the op holds has colour c: then c is the op's colour at every point (a
// blend of equal colours, or the one taken), and its value needs no per-primitive split.
bool uniformColor(const FieldProgram& P, const ActiveProgram& A, const FieldOp& op, const glm::vec3& c) {
  for (uint32_t k = 0; k < op.count; ++k)
    if (P.primitiveColor(op.primClass, A.indices[op.first + k]) != c) return false;
  return true;
}

// True when no primitive of the op can contribute a negative value (skeletal: intensity >= 0;
// convolution: weight >= 0; capsules never): then max(sum of a group, 0) is the sum of the group's
// max(p, 0), and primitives of one colour can be summed in one kernel call.
bool nonNegative(const FieldProgram& P, const ActiveProgram& A, const FieldOp& op) {
  for (uint32_t k = 0; k < op.count; ++k) {
    const uint32_t i = A.indices[op.first + k];
    if (op.primClass == PrimClass::Skeletal && !(P.skeletal[i].intensity >= 0.0f)) return false;
    if (op.primClass == PrimClass::Convolution && !(P.convolution.weight[i] >= 0.0f)) return false;
  }
  return true;
}

constexpr size_t kMaxGroups = 16;  // more colours in one op: a kernel call per primitive

// The op's primitives into groups of one colour (S.grouped, S.groupStart, S.groupColor), in the
// order of their first primitive; each primitive its own group, in order, when some could be
// negative (its weight is max(p, 0) alone) or there are over kMaxGroups colours. Returns the number
// of groups.
size_t groupByColor(const FieldProgram& P, const ActiveProgram& A, const FieldOp& op, RunScratch& S) {
  S.grouped.clear();
  S.groupStart.clear();
  S.groupColor.clear();
  const uint32_t* idx = A.indices.data() + op.first;
  bool grouping = nonNegative(P, A, op);
  for (uint32_t k = 0; grouping && k < op.count; ++k) {
    const glm::vec3 c = P.primitiveColor(op.primClass, idx[k]);
    if (std::find(S.groupColor.begin(), S.groupColor.end(), c) == S.groupColor.end()) S.groupColor.push_back(c);
    grouping = S.groupColor.size() <= kMaxGroups;
  }
  if (!grouping) {
    S.groupColor.clear();
    for (uint32_t k = 0; k < op.count; ++k) {
      S.grouped.push_back(idx[k]);
      S.groupStart.push_back(k);
      S.groupColor.push_back(P.primitiveColor(op.primClass, idx[k]));
    }
  } else {
    for (const glm::vec3& c : S.groupColor) {
      S.groupStart.push_back(uint32_t(S.grouped.size()));
      for (uint32_t k = 0; k < op.count; ++k)
        if (P.primitiveColor(op.primClass, idx[k]) == c) S.grouped.push_back(idx[k]);
    }
  }
  S.groupStart.push_back(op.count);
  return S.groupColor.size();
}

// A Prims op into entry s: the sum (weighted colours) or max (the larger's colour) of its
// primitives, one kernel call per group of one colour.
void primsOp(const ColorProgram& CP, const ActiveProgram& A, const FieldOp& op, RunScratch& S, int s, const float* x,
             const float* y, const float* z, int n, const glm::vec3& lo, const glm::vec3& hi) {
  const FieldProgram& P = CP.program;
  float* V = S.V(s);
  float* R = S.C(s, 0);
  float* G = S.C(s, 1);
  float* B = S.C(s, 2);
  float* W = S.weight.data();
  float* one = S.one.data();
  const glm::vec3 first = primsFallback(CP, op);
  S.zero[s] = S.uni[s] = 0;
  if (op.count == 0) {  // a specialised op whose primitives all miss the region: 0
    S.zero[s] = 1;
    setUniform(S, s, first);
    return;
  }
  const auto fieldOfOp = [&] {  // the op's value (and gradient) as the field evaluator has them
    contribution(P, op.primClass, A.indices.data() + op.first, int(op.count), op.combineMax, x, y, z, n, lo, hi, V,
                 S.grad ? S.G(s, 0) : nullptr, S.G(s, 1), S.G(s, 2));
  };
  if (uniformColor(P, A, op, first)) {
    fieldOfOp();
    setUniform(S, s, first);
    return;
  }
  std::fill(V, V + n, 0.0f);
  std::fill(W, W + n, 0.0f);
  if (op.combineMax) fillColor(S, s, n, first);
  else
    for (int k = 0; k < 3; ++k) std::fill(S.C(s, k), S.C(s, k) + n, 0.0f);
  const size_t groups = groupByColor(P, A, op, S);
  for (size_t g = 0; g < groups; ++g) {
    const glm::vec3 c = S.groupColor[g];
    contribution(P, op.primClass, S.grouped.data() + S.groupStart[g], int(S.groupStart[g + 1] - S.groupStart[g]),
                 op.combineMax, x, y, z, n, lo, hi, one);
    for (int i = 0; i < n; ++i) {
      if (op.combineMax) {
        if (one[i] > V[i]) {
          V[i] = one[i];
          R[i] = c.r;
          G[i] = c.g;
          B[i] = c.b;
        }
      } else {
        const float w = std::max(one[i], 0.0f);
        V[i] += one[i];
        W[i] += w;
        R[i] += w * c.r;
        G[i] += w * c.g;
        B[i] += w * c.b;
      }
    }
  }
  // With gradients, the value the groups summed is replaced by the whole op's (the evaluator's sum
  // order), the gradient with it: the groups give only the colours.
  if (S.grad) fieldOfOp();
  if (op.combineMax) return;
  for (int i = 0; i < n; ++i) {
    if (W[i] > 0.0f) {
      R[i] /= W[i];
      G[i] /= W[i];
      B[i] /= W[i];
    } else {
      R[i] = first.r;
      G[i] = first.g;
      B[i] = first.b;
    }
  }
}

// Entry base's colour at point i: the blend of entries base + k with weights w[k] (first kept when
// all 0: then false).
bool weighted(RunScratch& S, int base, int count, int i, const float* w) {
  float sum = 0.0f;
  glm::vec3 c(0.0f);
  for (int k = 0; k < count; ++k) {
    if (!(w[k] > 0.0f)) continue;
    sum += w[k];
    c += w[k] * glm::vec3(S.C(base + k, 0)[i], S.C(base + k, 1)[i], S.C(base + k, 2)[i]);
  }
  if (!(sum > 0.0f)) return false;
  c /= sum;
  S.C(base, 0)[i] = c.r;
  S.C(base, 1)[i] = c.g;
  S.C(base, 2)[i] = c.b;
  return true;
}

void setColor(RunScratch& S, int s, int i, const glm::vec3& c) {
  for (int k = 0; k < 3; ++k) S.C(s, k)[i] = c[k];
}

void take(RunScratch& S, int base, int k, int i) {
  for (int c = 0; c < 3; ++c) S.C(base, c)[i] = S.C(base + k, c)[i];
  if (S.grad)
    for (int a = 0; a < 3; ++a) S.G(base, a)[i] = S.G(base + k, a)[i];
}

// Entry base's gradient at point i: the sum of d[k] times entry base + k's, k < count, in the field
// evaluator's order (from 0 for a hyper-blend, from the first term for the R-functions and bounded
// blend, as it writes them).
void chainGradient(RunScratch& S, int base, int count, int i, const float* d, bool fromZero) {
  for (int a = 0; a < 3; ++a) {
    float g = fromZero ? 0.0f + d[0] * S.G(base, a)[i] : d[0] * S.G(base, a)[i];
    for (int k = 1; k < count; ++k) g += d[k] * S.G(base + k, a)[i];
    S.G(base, a)[i] = g;
  }
}

// A combining op over entries [base, base + count), result (value and colour) in entry base.
// A Sum whose first operand specialisation dropped (rule 2) where every weight is 0: the colour
// that first operand had, the Sum's empty colour.
void combine(const ColorProgram& CP, const FieldOp& op, RunScratch& S, int base, int n) {
  const FieldProgram& P = CP.program;
  const int count = int(op.count);
  const float T = P.threshold;
  const float* prm = P.params.data() + op.param;
  float w[64], vals[64], d[64];
  float* V0 = S.V(base);
  for (int i = 0; i < n; ++i) {
    switch (op.code) {
      case OpCode::Sum: {  // finish() folds sums to kFoldOperands operands: at most 64 colours weigh
        float v = 0.0f;
        for (int k = 0; k < count; ++k) {
          const float vk = S.V(base + k)[i];
          v += vk;
          if (k < 64) w[k] = std::max(vk, 0.0f);
        }
        if (!weighted(S, base, std::min(count, 64), i, w) && colorRule(op) == 2) setColor(S, base, i, ruleColor(CP, op));
        V0[i] = v;
        break;
      }
      case OpCode::Max:
      case OpCode::Min:
        for (int k = 1; k < count; ++k) {
          const float vk = S.V(base + k)[i];
          if (op.code == OpCode::Max ? vk > V0[i] : vk < V0[i]) {
            V0[i] = vk;
            take(S, base, k, i);
          }
        }
        break;
      case OpCode::HyperBlend: {
        // Weights p_k^q, scaled by the largest p^q (q is up to 64: small potentials would underflow).
        const int m = std::min(count, 64);
        float top = 0.0f;
        for (int k = 0; k < m; ++k) {
          vals[k] = S.V(base + k)[i];
          top = std::max(top, vals[k]);
        }
        for (int k = 0; k < m; ++k) w[k] = vals[k] > 0.0f ? std::pow(vals[k] / top, prm[0]) : 0.0f;
        weighted(S, base, m, i, w);
        V0[i] = hyperBlend(vals, m, prm[0], d);
        if (S.grad) chainGradient(S, base, m, i, d, true);
        break;
      }
      case OpCode::Difference: {  // the kept side's colour
        const float other = 2.0f * T - S.V(base + 1)[i];
        if (other < V0[i]) {
          V0[i] = other;
          if (S.grad)
            for (int a = 0; a < 3; ++a) S.G(base, a)[i] = -S.G(base + 1, a)[i];
        }
        break;
      }
      case OpCode::RUnion:
      case OpCode::RIntersection: {
        float d1, d2;
        const float s1 = V0[i] - T, s2 = S.V(base + 1)[i] - T;
        const float r = op.code == OpCode::RUnion ? rUnion(s1, s2, d1, d2) : rIntersection(s1, s2, d1, d2);
        w[0] = d1;
        w[1] = d2;
        weighted(S, base, 2, i, w);
        V0[i] = T + r;
        if (S.grad) chainGradient(S, base, 2, i, w, false);
        break;
      }
      case OpCode::BoundedBlend: {
        const float r = boundedBlend(V0[i] - T, S.V(base + 1)[i] - T, S.V(base + 2)[i] - T,
                                     BoundedBlendParams{prm[0], prm[1], prm[2], prm[3]}, d);
        weighted(S, base, 2, i, d);  // the bounding solid gives no colour
        V0[i] = T + r;
        if (S.grad) chainGradient(S, base, 3, i, d, false);
        break;
      }
      case OpCode::Remap: {
        float dd;
        V0[i] = remapPotential(V0[i], prm[0], prm[1], T, dd);
        if (S.grad)
          for (int a = 0; a < 3; ++a) S.G(base, a)[i] *= dd;
        break;
      }
      default: break;
    }
  }
}

// The value of skeletal point primitive p under affine map m at the points, into V: skeletalPotential
// (the sum's 0 + v, or the union's max(v, 0)) with an integer stiffness kPower + 1, written without
// its early return or branches so that the loop vectorises: beyond R, t is clamped at 0 and v is +0.
template <int kPower, bool kMax>
__attribute__((always_inline)) inline void mappedPointValues(const SpaceMap& m, const SkeletalPrimitive& p, const float* __restrict x,
                       const float* __restrict y, const float* __restrict z, int n, float* __restrict V) {
  const glm::mat3 L = m.linear;  // in locals, as the field's mapPoints has them
  const float l00 = L[0][0], l01 = L[0][1], l02 = L[0][2], l10 = L[1][0], l11 = L[1][1], l12 = L[1][2],
              l20 = L[2][0], l21 = L[2][1], l22 = L[2][2];
  const float o0 = m.origin.x, o1 = m.origin.y, o2 = m.origin.z;
  const float px = p.skeleton.p0.x, py = p.skeleton.p0.y, pz = p.skeleton.p0.z;
  const float r2 = p.radius * p.radius, I = p.intensity;
  for (int i = 0; i < n; ++i) {
    const float dx = x[i] - o0, dy = y[i] - o1, dz = z[i] - o2;
    const float ex = l00 * dx + l10 * dy + l20 * dz - px;
    const float ey = l01 * dx + l11 * dy + l21 * dz - py;
    const float ez = l02 * dx + l12 * dy + l22 * dz - pz;
    const float u = 1.0f - (ex * ex + ey * ey + ez * ez) / r2;
    const float t = 0.5f * (u + std::fabs(u));  // max(u, 0), exactly, with no select to thread jumps through
    float tk1 = 1.0f;  // powStiffness's multiply chain, written out
    if constexpr (kPower >= 1) tk1 *= t;
    if constexpr (kPower >= 2) tk1 *= t;
    if constexpr (kPower >= 3) tk1 *= t;
    const float v = I * tk1 * t;
    if constexpr (kMax) V[i] = 0.5f * (v + std::fabs(v));
    else V[i] = 0.0f + v;
  }
}

template <bool kMax>
__attribute__((always_inline)) inline void mappedPointValues(const SpaceMap& m, const SkeletalPrimitive& p,
                                                             const float* x, const float* y, const float* z, int n,
                                                             float* V) {
  const float K = p.stiffness;
  if (K == 1.0f) mappedPointValues<0, kMax>(m, p, x, y, z, n, V);
  else if (K == 2.0f) mappedPointValues<1, kMax>(m, p, x, y, z, n, V);
  else if (K == 3.0f) mappedPointValues<2, kMax>(m, p, x, y, z, n, V);
  else mappedPointValues<3, kMax>(m, p, x, y, z, n, V);
}

// The loops above, cloned for AVX-512 and AVX2 (field_program_detail.h); this file is compiled
// without contraction (engine/core/CMakeLists.txt), so every clone computes the same values.
ANIMORPH_KERNEL __attribute__((noinline)) void mappedPointLoop(const SpaceMap& m, const SkeletalPrimitive& p,
                                                               bool combineMax, const float* x, const float* y,
                                                               const float* z, int n, float* V) {
  if (combineMax) mappedPointValues<true>(m, p, x, y, z, n, V);
  else mappedPointValues<false>(m, p, x, y, z, n, V);
}

// mappedPointValues with the gradient, for a walk with gradients: the field evaluator's fused loop
// (field_program_evaluate.cpp, mappedPointRun with gradients), its operations in its order, so the
// value and gradient are the evaluator's bit for bit: within R, 0 + v (a sum) or v where v > 0 (a
// union), and gf times the offset; elsewhere +0; the local gradient mapped back by L^T.
template <int kPower, bool kMax>
__attribute__((always_inline)) inline void mappedPointGradients(const SpaceMap& m, const SkeletalPrimitive& p,
                                                                const float* __restrict x, const float* __restrict y,
                                                                const float* __restrict z, int n, float* __restrict V,
                                                                float* __restrict gx, float* __restrict gy,
                                                                float* __restrict gz) {
  const glm::mat3 L = m.linear;
  const float l00 = L[0][0], l01 = L[0][1], l02 = L[0][2], l10 = L[1][0], l11 = L[1][1], l12 = L[1][2],
              l20 = L[2][0], l21 = L[2][1], l22 = L[2][2];
  const float o0 = m.origin.x, o1 = m.origin.y, o2 = m.origin.z;
  const float px = p.skeleton.p0.x, py = p.skeleton.p0.y, pz = p.skeleton.p0.z;
  const float r2 = p.radius * p.radius, I = p.intensity, K = p.stiffness;
  for (int i = 0; i < n; ++i) {
    const float dx = x[i] - o0, dy = y[i] - o1, dz = z[i] - o2;
    const float qx = l00 * dx + l10 * dy + l20 * dz;
    const float qy = l01 * dx + l11 * dy + l21 * dz;
    const float qz = l02 * dx + l12 * dy + l22 * dz;
    const float ex = qx - px, ey = qy - py, ez = qz - pz;
    const float d2 = ex * ex + ey * ey + ez * ez;
    const bool within = d2 < r2;
    const float t = 1.0f - d2 / r2;
    float tk1 = 1.0f;
    if constexpr (kPower >= 1) tk1 *= t;
    if constexpr (kPower >= 2) tk1 *= t;
    if constexpr (kPower >= 3) tk1 *= t;
    const float gf = -2.0f * I * K / r2 * tk1;
    const float v = I * tk1 * t;
    float fv, ax, ay, az;
    if constexpr (kMax) {
      const bool keep = within && v > 0.0f;
      fv = keep ? v : 0.0f;
      ax = keep ? gf * ex : 0.0f;
      ay = keep ? gf * ey : 0.0f;
      az = keep ? gf * ez : 0.0f;
    } else {
      fv = within ? 0.0f + v : 0.0f;
      ax = within ? 0.0f + gf * ex : 0.0f;
      ay = within ? 0.0f + gf * ey : 0.0f;
      az = within ? 0.0f + gf * ez : 0.0f;
    }
    V[i] = fv;
    gx[i] = l00 * ax + l01 * ay + l02 * az;
    gy[i] = l10 * ax + l11 * ay + l12 * az;
    gz[i] = l20 * ax + l21 * ay + l22 * az;
  }
}

template <bool kMax>
__attribute__((always_inline)) inline void mappedPointGradients(const SpaceMap& m, const SkeletalPrimitive& p,
                                                                const float* x, const float* y, const float* z, int n,
                                                                float* V, float* gx, float* gy, float* gz) {
  const float K = p.stiffness;
  if (K == 1.0f) mappedPointGradients<0, kMax>(m, p, x, y, z, n, V, gx, gy, gz);
  else if (K == 2.0f) mappedPointGradients<1, kMax>(m, p, x, y, z, n, V, gx, gy, gz);
  else if (K == 3.0f) mappedPointGradients<2, kMax>(m, p, x, y, z, n, V, gx, gy, gz);
  else mappedPointGradients<3, kMax>(m, p, x, y, z, n, V, gx, gy, gz);
}

// mappedPointGradients, cloned as mappedPointLoop.
ANIMORPH_KERNEL __attribute__((noinline)) void mappedPointGradientLoop(const SpaceMap& m, const SkeletalPrimitive& p,
                                                                       bool combineMax, const float* x, const float* y,
                                                                       const float* z, int n, float* V, float* gx,
                                                                       float* gy, float* gz) {
  if (combineMax) mappedPointGradients<true>(m, p, x, y, z, n, V, gx, gy, gz);
  else mappedPointGradients<false>(m, p, x, y, z, n, V, gx, gy, gz);
}

// One Sum operand's weights w = max(v, 0) (0 where v is NaN) added to W, and w times its colour
// (rows r, g, b, or the constant c where r is null) to R, G, B. Cloned as mappedPointLoop.
ANIMORPH_KERNEL __attribute__((noinline)) void weighOperand(const float* __restrict v, const float* __restrict r,
                                                            const float* __restrict g, const float* __restrict b,
                                                            const glm::vec3 c, int n, float* __restrict W,
                                                            float* __restrict R, float* __restrict G,
                                                            float* __restrict B) {
  if (!r) {
    const float cr = c.r, cg = c.g, cb = c.b;
    for (int i = 0; i < n; ++i) {
      const float w = v[i] > 0.0f ? v[i] : 0.0f;
      W[i] += w;
      R[i] += w * cr;
      G[i] += w * cg;
      B[i] += w * cb;
    }
    return;
  }
  for (int i = 0; i < n; ++i) {
    const float w = v[i] > 0.0f ? v[i] : 0.0f;
    W[i] += w;
    R[i] += w * r[i];
    G[i] += w * g[i];
    B[i] += w * b[i];
  }
}

// The value (and gradient) of a Sum over entries [base, base + count) into base, as the field
// evaluator sums them: entries +0 everywhere skipped, the first other one copied (0 + a is a), the
// rest added in their order; every entry +0: base flagged +0.
void sumValues(RunScratch& S, int base, int count, int n) {
  int k0 = 0;
  while (k0 < count && S.zero[base + k0]) ++k0;
  if (k0 == count) {
    S.zero[base] = 1;
    return;
  }
  const int rows = S.grad ? 4 : 1;  // the value, then the gradient's x, y, z
  for (int r = 0; k0 > 0 && r < rows; ++r) {
    const float* from = S.V(base + k0) + r * kRun;
    std::copy(from, from + n, S.V(base) + r * kRun);
  }
  S.zero[base] = 0;
  float *__restrict v = S.V(base), *__restrict gx = S.G(base, 0), *__restrict gy = S.G(base, 1),
                    *__restrict gz = S.G(base, 2);
  for (int k = k0 + 1; k < count; ++k) {
    if (S.zero[base + k]) continue;
    const float *__restrict a = S.V(base + k), *__restrict ax = S.G(base + k, 0), *__restrict ay = S.G(base + k, 1),
                            *__restrict az = S.G(base + k, 2);
    if (!S.grad) {
      for (int i = 0; i < n; ++i) v[i] += a[i];
      continue;
    }
    for (int i = 0; i < n; ++i) {  // the four rows in one loop (a sub-block's dozen points: one pass)
      v[i] += a[i];
      gx[i] += ax[i];
      gy[i] += ay[i];
      gz[i] += az[i];
    }
  }
}

// A Sum over entries [base, base + op.count) into base, as combine() gives it, operand by operand
// over all the points (loops the compiler vectorises): entries that are +0 everywhere are skipped
// (their weight is 0, and v + 0 is v), one-coloured entries add their weight times a constant.
// The weights, sums and quotients are combine()'s, in the same order. One colour when every
// operand that can weigh and the colour where none weighs are the same.
void sumOp(const ColorProgram& CP, const FieldOp& op, RunScratch& S, int base, int n) {
  const int count = int(op.count), weighing = std::min(count, 64);  // combine(): at most 64 colours weigh
  const bool ruleEmpty = colorRule(op) == 2;
  const glm::vec3 emptyRule = ruleEmpty ? ruleColor(CP, op) : glm::vec3(0.0f);
  bool oneColor = ruleEmpty || S.uni[base];
  const glm::vec3 c0 = ruleEmpty ? emptyRule : S.uc[base];
  for (int k = 0; k < count; ++k) {
    const int e = base + k;
    if (S.zero[e]) continue;
    if (k < weighing) oneColor = oneColor && S.uni[e] && S.uc[e] == c0;
  }
  if (oneColor) {  // (every operand +0: no weight anywhere, the colour c0 where none weighs)
    sumValues(S, base, count, n);
    setUniform(S, base, c0);
    return;
  }
  float* W = S.weight.data();
  float* R = S.acc.data();
  float* G = R + kRun;
  float* B = R + 2 * kRun;
  std::fill(W, W + n, 0.0f);
  std::fill(S.acc.begin(), S.acc.end(), 0.0f);
  for (int k = 0; k < weighing; ++k) {
    const int e = base + k;
    if (S.zero[e]) continue;
    const float* vk = S.V(e);
    if (S.uni[e]) weighOperand(vk, nullptr, nullptr, nullptr, S.uc[e], n, W, R, G, B);
    else weighOperand(vk, S.C(e, 0), S.C(e, 1), S.C(e, 2), glm::vec3(0.0f), n, W, R, G, B);
  }
  // Where no operand weighs: the rule's colour, or the first operand's (kept).
  if (ruleEmpty || S.uni[base]) fillColor(S, base, n, ruleEmpty ? emptyRule : S.uc[base]);
  float *R0 = S.C(base, 0), *G0 = S.C(base, 1), *B0 = S.C(base, 2);
  for (int i = 0; i < n; ++i) {
    if (W[i] > 0.0f) {
      R0[i] = R[i] / W[i];
      G0[i] = G[i] / W[i];
      B0[i] = B[i] / W[i];
    }
  }
  S.uni[base] = 0;
  sumValues(S, base, count, n);
}

// BeginMap ops[oi] of an affine map, then one skeletal point primitive of one colour, then its
// EndMap (a meta-primitive's instance): its value at the points in one loop into entry s, its
// colour one constant (as primsOp gives them without mapping the points). False when the ops are
// not of that form (nothing written).
bool fusedMappedPoint(const ColorProgram& CP, const ActiveProgram& A, size_t oi, RunScratch& S, int s, const float* x,
                      const float* y, const float* z, int n) {
  const FieldProgram& P = CP.program;
  const SpaceMap& m = P.maps[A.ops[oi].first];
  if (m.kind != SpaceMapKind::Affine || oi + 2 >= A.ops.size()) return false;
  const FieldOp& prims = A.ops[oi + 1];
  if (prims.code != OpCode::Prims || prims.primClass != PrimClass::Skeletal || prims.count != 1 ||
      A.ops[oi + 2].code != OpCode::EndMap)
    return false;
  const SkeletalPrimitive& p = P.skeletal[A.indices[prims.first]];
  const glm::vec3 first = primsFallback(CP, prims);
  const float K = p.stiffness;
  if (p.skeleton.kind != SkeletonKind::Point || !(p.radius > 0.0f) ||
      !(K == 1.0f || K == 2.0f || K == 3.0f || K == 4.0f) || !uniformColor(P, A, prims, first))
    return false;
  if (S.grad) mappedPointGradientLoop(m, p, prims.combineMax, x, y, z, n, S.V(s), S.G(s, 0), S.G(s, 1), S.G(s, 2));
  else mappedPointLoop(m, p, prims.combineMax, x, y, z, n, S.V(s));
  S.zero[s] = 0;
  setUniform(S, s, first);
  return true;
}

// True (with c) when the program can give only one colour: every primitive it holds, every
// fallback colour (a Prims op's first primitive, a constant's, a Sum's, a skipped map's) is c.
// Every op's colour is a blend of, or a choice among, these: c wherever it is evaluated.
bool singleColor(const ColorProgram& CP, const ActiveProgram& A, glm::vec3& c) {
  bool any = false;
  auto same = [&](const glm::vec3& ck) {
    if (!any) c = ck;
    any = true;
    return ck == c;
  };
  for (const FieldOp& op : A.ops) {
    switch (op.code) {
      case OpCode::Prims:
        if (!same(primsFallback(CP, op))) return false;
        if (!uniformColor(CP.program, A, op, c)) return false;
        break;
      case OpCode::Const:
        if (!same(constColor(CP, op))) return false;
        break;
      case OpCode::BeginMap:
        if (op.first < CP.mapEmptyColor.size() && !same(CP.mapEmptyColor[op.first])) return false;
        break;
      default: break;
    }
    if (colorRule(op) != 0 && !same(ruleColor(CP, op))) return false;
  }
  return any;
}

// From BeginMap ops[oi]: the index of its EndMap.
size_t matchingEnd(const ActiveProgram& A, size_t oi) {
  for (int open = 1; open > 0;) {
    const OpCode c = A.ops[++oi].code;
    open += c == OpCode::BeginMap ? 1 : c == OpCode::EndMap ? -1 : 0;
  }
  return oi;
}

// Sizes the scratch for one run of program P and sets the points of level 0.
void prepareRun(const FieldProgram& P, RunScratch& S, const float* x, const float* y, const float* z, int n) {
  const int depth = P.maxMapDepth() + 1;
  S.stack.resize(size_t(std::max(1, P.maxStack())) * RunScratch::kRows * kRun);
  S.uni.assign(size_t(std::max(1, P.maxStack())), 0);
  S.zero.assign(size_t(std::max(1, P.maxStack())), 0);
  S.uc.resize(size_t(std::max(1, P.maxStack())));
  S.acc.resize(3 * kRun);
  S.coords.resize(size_t(depth) * 3 * kRun);
  S.one.resize(kRun);
  S.weight.resize(kRun);
  for (auto* l : {&S.lx, &S.ly, &S.lz}) l->resize(size_t(depth));
  S.lo.resize(size_t(depth));
  S.hi.resize(size_t(depth));
  S.lx[0] = x;
  S.ly[0] = y;
  S.lz[0] = z;
  boxOf(x, y, z, n, S.lo[0], S.hi[0]);
}

// Enters map m: the points of the next level are the current level's in the map's local space.
void enterMap(const SpaceMap& m, RunScratch& S, int& level, int n) {
  float* o = S.coords.data() + size_t(level + 1) * 3 * kRun;
  const size_t l = size_t(level);
  if (m.kind == SpaceMapKind::Affine) {  // linear * (x - origin), in locals (a loop that vectorises)
    const glm::mat3 L = m.linear;
    const float l00 = L[0][0], l01 = L[0][1], l02 = L[0][2], l10 = L[1][0], l11 = L[1][1], l12 = L[1][2],
                l20 = L[2][0], l21 = L[2][1], l22 = L[2][2];
    const float o0 = m.origin.x, o1 = m.origin.y, o2 = m.origin.z;
    const float *__restrict ix = S.lx[l], *__restrict iy = S.ly[l], *__restrict iz = S.lz[l];
    float *__restrict ox = o, *__restrict oy = o + kRun, *__restrict oz = o + 2 * kRun;
    for (int i = 0; i < n; ++i) {
      const float dx = ix[i] - o0, dy = iy[i] - o1, dz = iz[i] - o2;
      ox[i] = l00 * dx + l10 * dy + l20 * dz;
      oy[i] = l01 * dx + l11 * dy + l21 * dz;
      oz[i] = l02 * dx + l12 * dy + l22 * dz;
    }
  } else {
    for (int i = 0; i < n; ++i) {
      const glm::vec3 q = m.toLocal({S.lx[l][i], S.ly[l][i], S.lz[l][i]});
      o[i] = q.x;
      o[kRun + i] = q.y;
      o[2 * kRun + i] = q.z;
    }
  }
  ++level;
  S.lx[size_t(level)] = o;
  S.ly[size_t(level)] = o + kRun;
  S.lz[size_t(level)] = o + 2 * kRun;
  boxOf(o, o + kRun, o + 2 * kRun, n, S.lo[size_t(level)], S.hi[size_t(level)]);
}

// Entry s just pushed by op: where its value is <= 0, colorRule 3's colour.
void applyValueRule(const ColorProgram& CP, const FieldOp& op, RunScratch& S, int s, int n) {
  if (colorRule(op) != 3) return;
  const glm::vec3 c = ruleColor(CP, op);
  if (S.zero[s]) {  // <= 0 everywhere
    setUniform(S, s, c);
    return;
  }
  if (S.uni[s] && S.uc[s] == c) return;
  materialise(S, s, n);
  const float* V = S.V(s);
  for (int i = 0; i < n; ++i)
    if (!(V[i] > 0.0f)) setColor(S, s, i, c);
}

// Pushes a constant value of one colour (gradient 0) into entry s (+0: only flagged).
void pushConstant(RunScratch& S, int s, int n, float value, const glm::vec3& c) {
  S.zero[s] = value == 0.0f && !std::signbit(value);
  if (!S.zero[s]) {
    std::fill(S.V(s), S.V(s) + n, value);
    zeroGradient(S, s, n);
  }
  setUniform(S, s, c);
}

// Leaving map m (level is the parent's): entry s's local gradient mapped back to the parent's
// space, grad = J^T grad_local, as the field evaluator's pullBackGradient computes it. An entry +0
// everywhere keeps its zero gradient.
void pullBackGradient(const SpaceMap& m, RunScratch& S, int s, int level, int n) {
  if (!S.grad || S.zero[s]) return;
  float *__restrict gx = S.G(s, 0), *__restrict gy = S.G(s, 1), *__restrict gz = S.G(s, 2);
  if (m.kind == SpaceMapKind::Affine) {
    const glm::mat3 L = m.linear;
    const float l00 = L[0][0], l01 = L[0][1], l02 = L[0][2], l10 = L[1][0], l11 = L[1][1], l12 = L[1][2],
                l20 = L[2][0], l21 = L[2][1], l22 = L[2][2];
    for (int i = 0; i < n; ++i) {
      const float a = gx[i], b = gy[i], c = gz[i];
      gx[i] = l00 * a + l01 * b + l02 * c;
      gy[i] = l10 * a + l11 * b + l12 * c;
      gz[i] = l20 * a + l21 * b + l22 * c;
    }
    return;
  }
  const size_t l = size_t(level);
  for (int i = 0; i < n; ++i) {
    glm::mat3 J;
    m.toLocal({S.lx[l][i], S.ly[l][i], S.lz[l][i]}, &J);
    const glm::vec3 g = glm::transpose(J) * glm::vec3(gx[i], gy[i], gz[i]);
    gx[i] = g.x;
    gy[i] = g.y;
    gz[i] = g.z;
  }
}

// The walk's result: the field minus the threshold into f (when not null) and its gradient into
// gx, gy, gz (when not null), as the field evaluator's last step writes them.
void writeField(const FieldProgram& P, RunScratch& S, int sp, int n, float* f, float* gx, float* gy, float* gz) {
  const bool none = sp == 0 || S.zero[0];
  for (int i = 0; f && i < n; ++i) f[i] = (none ? 0.0f : S.V(0)[i]) - P.threshold;
  if (!gx) return;
  float* g[3] = {gx, gy, gz};
  for (int a = 0; a < 3; ++a) {
    if (none) std::fill(g[a], g[a] + n, 0.0f);
    else std::copy(S.G(0, a), S.G(0, a) + n, g[a]);
  }
}

// The ops of a specialised program over one run of n points (n <= kRun): colours into out.
// skipMissedMaps: a map whose primitives reach none of the points is its empty value there, with
// its empty colour, without mapping the points (as the field evaluator does): the same result.
// With S.grad, the field and its gradient too (writeField: f may be null, gx not).
void runColors(const ColorProgram& CP, const ActiveProgram& A, RunScratch& S, const float* x, const float* y,
               const float* z, int n, glm::vec4* out, bool skipMissedMaps, float* f = nullptr,
               float* gx = nullptr, float* gy = nullptr, float* gz = nullptr) {
  const FieldProgram& P = CP.program;
  prepareRun(P, S, x, y, z, n);
  int sp = 0, level = 0;
  for (size_t oi = 0; oi < A.ops.size(); ++oi) {
    const FieldOp& op = A.ops[oi];
    const size_t l = size_t(level);
    switch (op.code) {
      case OpCode::Prims:
        primsOp(CP, A, op, S, sp, S.lx[l], S.ly[l], S.lz[l], n, S.lo[l], S.hi[l]);
        applyValueRule(CP, op, S, sp, n);
        ++sp;
        break;
      case OpCode::Const:
        pushConstant(S, sp, n, op.emptyValue, constColor(CP, op));
        ++sp;
        break;
      case OpCode::BeginMap: {
        const Bounds& r = P.mapReach(op.first);
        if (skipMissedMaps &&
            (r.empty() || glm::any(glm::greaterThan(r.min, S.hi[0])) || glm::any(glm::lessThan(r.max, S.lo[0])))) {
          oi = matchingEnd(A, oi);
          pushConstant(S, sp, n, A.ops[oi].emptyValue,
                       op.first < CP.mapEmptyColor.size() ? CP.mapEmptyColor[op.first] : clayLinear());
          applyValueRule(CP, A.ops[oi], S, sp, n);
          ++sp;
          break;
        }
        if (fusedMappedPoint(CP, A, oi, S, sp, S.lx[l], S.ly[l], S.lz[l], n)) {
          applyValueRule(CP, A.ops[oi + 1], S, sp, n);
          applyValueRule(CP, A.ops[oi + 2], S, sp, n);
          oi += 2;
          ++sp;
          break;
        }
        enterMap(P.maps[op.first], S, level, n);
        break;
      }
      case OpCode::EndMap:
        --level;
        pullBackGradient(P.maps[op.first], S, sp - 1, level, n);
        applyValueRule(CP, op, S, sp - 1, n);
        break;
      default: {
        const int base = sp - int(op.count);
        if (op.code == OpCode::Sum) {
          sumOp(CP, op, S, base, n);
        } else {
          for (int k = 0; k < int(op.count); ++k) materialise(S, base + k, n);
          combine(CP, op, S, base, n);
        }
        applyValueRule(CP, op, S, base, n);
        sp = base + 1;
      }
    }
  }
  if (S.grad) writeField(P, S, sp, n, f, gx, gy, gz);
  if (sp > 0 && S.uni[0]) {
    std::fill(out, out + n, glm::vec4(glm::clamp(S.uc[0], 0.0f, 1.0f), 1.0f));
    return;
  }
  for (int i = 0; i < n; ++i) {
    glm::vec3 c = sp > 0 ? glm::vec3(S.C(0, 0)[i], S.C(0, 1)[i], S.C(0, 2)[i]) : clayLinear();
    out[i] = glm::vec4(glm::clamp(c, 0.0f, 1.0f), 1.0f);
  }
}

// Points order[begin, end) (at most kRun): evaluated with the primitives reaching their box.
void evaluateRun(const ColorProgram& CP, const glm::vec3* points, const uint32_t* order, int n, glm::vec4* out,
                 RunScratch& S) {
  float xyz[3 * kRun];
  Bounds box;
  for (int i = 0; i < n; ++i) {
    const glm::vec3& p = points[order[i]];
    xyz[i] = p.x;
    xyz[kRun + i] = p.y;
    xyz[2 * kRun + i] = p.z;
    box.add(p);
  }
  CP.program.primitivesReaching(box, S.reach);
  CP.program.specialise(S.reach, S.active);
  glm::vec4 colors[kRun];
  glm::vec3 c;
  if (singleColor(CP, S.active, c)) std::fill(colors, colors + n, glm::vec4(glm::clamp(c, 0.0f, 1.0f), 1.0f));
  else runColors(CP, S.active, S, xyz, xyz + kRun, xyz + 2 * kRun, n, colors, true);
  for (int i = 0; i < n; ++i) out[order[i]] = colors[i];
}

}  // namespace

ColorProgram::ColorProgram(const FieldProgram& p) : program(p) {
  primColor.assign(p.primitiveCount(), clayLinear());
  for (const FieldOp& op : p.ops)
    if (op.code == OpCode::Prims)
      for (uint32_t k = 0; k < op.count && op.primBegin + k < primColor.size(); ++k)
        primColor[op.primBegin + k] = p.primitiveColor(op.primClass, op.first + k);
  // The whole walk where no primitive contributes: every Prims op 0 in its first primitive's colour,
  // the operators' rules on these (the same code as at points, one point).
  emptyColor.assign(p.ops.size(), clayLinear());
  mapEmptyColor.assign(p.maps.size(), clayLinear());
  RunScratch S;
  S.stack.resize(size_t(std::max(1, p.maxStack())) * RunScratch::kRows * kRun);
  S.one.resize(kRun);
  S.weight.resize(kRun);
  int sp = 0;
  for (size_t i = 0; i < p.ops.size(); ++i) {
    const FieldOp& op = p.ops[i];
    switch (op.code) {
      case OpCode::Prims:
      case OpCode::Const:
        S.V(sp)[0] = op.code == OpCode::Prims ? 0.0f : op.emptyValue;
        setColor(S, sp, 0, op.code == OpCode::Prims ? primsFallback(*this, op) : clayLinear());
        ++sp;
        break;
      case OpCode::BeginMap: break;
      case OpCode::EndMap:
        if (op.first < mapEmptyColor.size() && sp > 0)
          mapEmptyColor[op.first] = glm::vec3(S.C(sp - 1, 0)[0], S.C(sp - 1, 1)[0], S.C(sp - 1, 2)[0]);
        break;
      default: {
        const int base = sp - int(op.count);
        if (base < 0) return;  // malformed (finish() leaves none)
        combine(*this, op, S, base, 1);
        sp = base + 1;
      }
    }
    if (sp > 0) emptyColor[i] = glm::vec3(S.C(sp - 1, 0)[0], S.C(sp - 1, 1)[0], S.C(sp - 1, 2)[0]);
  }
}

void SurfaceColorEvaluator::evaluate(const FieldProgram& program, const glm::vec3* points, size_t n, glm::vec4* out,
                                     int threads) {
  if (n == 0) return;
  evaluate(ColorProgram(program), points, n, out, threads);
}

void SurfaceColorEvaluator::evaluate(const ColorProgram& program, const glm::vec3* points, size_t n, glm::vec4* out,
                                     int threads) {
  if (n == 0) return;
  // Sort the points along a Morton curve of 1024 cells per side of their box, so each run of
  // consecutive points is compact (a small box, few primitives reaching it).
  Bounds all;
  for (size_t i = 0; i < n; ++i) all.add(points[i]);
  const float cell = std::max(all.size().x, std::max(all.size().y, all.size().z)) / 1024.0f + 1e-20f;
  auto spread = [](uint64_t v) {  // 10 bits to every third bit
    v &= 0x3ff;
    v = (v | (v << 16)) & 0x30000ff;
    v = (v | (v << 8)) & 0x300f00f;
    v = (v | (v << 4)) & 0x30c30c3;
    v = (v | (v << 2)) & 0x9249249;
    return v;
  };
  keys_.resize(n);
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::ivec3 c = glm::clamp(glm::ivec3((points[i] - all.min) / cell), 0, 1023);
    keys_[i] = spread(uint64_t(c.x)) | spread(uint64_t(c.y)) << 1 | spread(uint64_t(c.z)) << 2;
    order_[i] = uint32_t(i);
  }
  std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) { return keys_[a] < keys_[b]; });
  const size_t runs = (n + kRun - 1) / kRun;
  tbb::enumerable_thread_specific<RunScratch> scratch;
  auto body = [&](const tbb::blocked_range<size_t>& r) {
    RunScratch& S = scratch.local();
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const size_t b = k * kRun;
      evaluateRun(program, points, order_.data() + b, int(std::min<size_t>(kRun, n - b)), out, S);
    }
  };
  if (threads == 1 || runs == 1) {
    body(tbb::blocked_range<size_t>(0, runs));
    return;
  }
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] { tbb::parallel_for(tbb::blocked_range<size_t>(0, runs, 4), body); });
}

void SurfaceColorEvaluator::evaluateActive(const ColorProgram& program, const ActiveProgram& active, const float* x,
                                           const float* y, const float* z, int n, glm::vec4* out) {
  if (glm::vec3 c; singleColor(program, active, c)) {
    std::fill(out, out + n, glm::vec4(glm::clamp(c, 0.0f, 1.0f), 1.0f));
    return;
  }
  run_.grad = false;
  for (int b = 0; b < n; b += kRun)
    runColors(program, active, run_, x + b, y + b, z + b, std::min(kRun, n - b), out + b, true);
}

void SurfaceColorEvaluator::evaluateActiveWithGradient(const ColorProgram& program, const ActiveProgram& active,
                                                       const float* x, const float* y, const float* z, int n,
                                                       glm::vec4* out, float* f, float* gx, float* gy, float* gz) {
  if (glm::vec3 c; singleColor(program, active, c)) {  // the colour is known: the field's own walk is cheaper
    std::fill(out, out + n, glm::vec4(glm::clamp(c, 0.0f, 1.0f), 1.0f));
    if (!f) {
      fScratch_.resize(size_t(std::max(n, 0)));
      f = fScratch_.data();
    }
    field_.evaluate(program.program, active, x, y, z, n, f, gx, gy, gz);
    return;
  }
  run_.grad = true;
  for (int b = 0; b < n; b += kRun)
    runColors(program, active, run_, x + b, y + b, z + b, std::min(kRun, n - b), out + b, true, f ? f + b : nullptr,
              gx + b, gy + b, gz + b);
  run_.grad = false;
}

void SurfaceColorEvaluator::evaluateFull(const FieldProgram& program, const glm::vec3* points, size_t n,
                                         glm::vec4* out) {
  const ColorProgram cp(program);
  program.specialiseAll(run_.active);
  run_.grad = false;
  float xyz[3 * kRun];
  for (size_t b = 0; b < n; b += kRun) {
    const int m = int(std::min<size_t>(kRun, n - b));
    for (int i = 0; i < m; ++i) {
      xyz[i] = points[b + size_t(i)].x;
      xyz[kRun + i] = points[b + size_t(i)].y;
      xyz[2 * kRun + i] = points[b + size_t(i)].z;
    }
    runColors(cp, run_.active, run_, xyz, xyz + kRun, xyz + 2 * kRun, m, out + b, false);
  }
}

glm::vec3 SurfaceColorEvaluator::evaluatePoint(const FieldProgram& program, const glm::vec3& p) {
  glm::vec4 c;
  evaluate(program, &p, 1, &c, 1);
  return glm::vec3(c);
}

}  // namespace animorph
