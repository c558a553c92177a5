// FieldProgram, part 4 of 4: batch evaluation of values and gradients.
#include "core/field/field_program.h"

#include <algorithm>
#include <functional>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/field/convolution_segment.h"
#include "core/field/field_program_detail.h"
#include "core/field/potential.h"

namespace animorph {

namespace {
constexpr int kChunk = 1024;

// The value of a map subtree made of one affine map over one point primitive, at every point of
// the run: the map loop's transform, then skeletalPotential's operations in its order.
// Without gradients, t is clamped at 0 instead of its early return, so the loop vectorises (in
// runChunk's clones). The Prims op this replaces starts at 0 and adds v where d^2 < R^2 (a sum)
// or keeps the larger (a union); 0 + v and max(0, v) here give the same values, and v is +-0
// beyond R. With gradients, the skeletal kernel adds v and gf * d to zeros (a sum: 0 + v) or keeps
// them where v > 0 (a union), for the points within R (the others keep +0), and EndMap maps the
// local gradient back by L^T, zeros included: the same operations, point by point.
template <int kPower, bool kMax, bool kGrad>
__attribute__((always_inline)) inline void mappedPointRun(const SpaceMap& m, const SkeletalPrimitive& p,
                                                          const float* __restrict ix, const float* __restrict iy,
                                                          const float* __restrict iz, int n, float* __restrict f,
                                                          float* __restrict gx, float* __restrict gy,
                                                          float* __restrict gz) {
  const glm::mat3 L = m.linear;
  const float l00 = L[0][0], l01 = L[0][1], l02 = L[0][2], l10 = L[1][0], l11 = L[1][1], l12 = L[1][2],
              l20 = L[2][0], l21 = L[2][1], l22 = L[2][2];
  const float o0 = m.origin.x, o1 = m.origin.y, o2 = m.origin.z;
  const float px = p.skeleton.p0.x, py = p.skeleton.p0.y, pz = p.skeleton.p0.z;
  const float r2 = p.radius * p.radius, I = p.intensity, K = p.stiffness;
  for (int i = 0; i < n; ++i) {
    float dx = ix[i] - o0, dy = iy[i] - o1, dz = iz[i] - o2;
    float qx = l00 * dx + l10 * dy + l20 * dz;
    float qy = l01 * dx + l11 * dy + l21 * dz;
    float qz = l02 * dx + l12 * dy + l22 * dz;
    float ex = qx - px, ey = qy - py, ez = qz - pz;
    float d2 = ex * ex + ey * ey + ez * ez;
    if constexpr (!kGrad) {
      float t = 1.0f - d2 / r2;
      t = t > 0.0f ? t : 0.0f;  // beyond R (or NaN): v is +-0
      float tk1 = 1.0f;         // powStiffness's multiply chain, written out
      if constexpr (kPower >= 1) tk1 *= t;
      if constexpr (kPower >= 2) tk1 *= t;
      if constexpr (kPower >= 3) tk1 *= t;
      float v = I * tk1 * t;
      if constexpr (kMax) f[i] = v > 0.0f ? v : 0.0f;
      else f[i] = 0.0f + v;
    } else {
      bool within = d2 < r2;
      float t = 1.0f - d2 / r2;
      float tk1 = 1.0f;  // powStiffness's multiply chain, written out
      if constexpr (kPower >= 1) tk1 *= t;
      if constexpr (kPower >= 2) tk1 *= t;
      if constexpr (kPower >= 3) tk1 *= t;
      float gf = -2.0f * I * K / r2 * tk1;
      float v = I * tk1 * t;
      float fv, ax, ay, az;
      if constexpr (kMax) {
        bool keep = within && v > 0.0f;
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
      f[i] = fv;
      gx[i] = l00 * ax + l01 * ay + l02 * az;
      gy[i] = l10 * ax + l11 * ay + l12 * az;
      gz[i] = l20 * ax + l21 * ay + l22 * az;
    }
  }
}

// mappedPointRun (with gradients when gx is given) for a point primitive with R > 0 and an integer
// stiffness 1..4 (true); else false (the ops run one by one).
template <bool kMax, bool kGrad>
__attribute__((always_inline)) inline bool mappedPointStiffness(const SpaceMap& m, const SkeletalPrimitive& p,
                                                                const float* x, const float* y, const float* z,
                                                                int n, float* f, float* gx, float* gy, float* gz) {
  const float K = p.stiffness;
  if (K == 1.0f) mappedPointRun<0, kMax, kGrad>(m, p, x, y, z, n, f, gx, gy, gz);
  else if (K == 2.0f) mappedPointRun<1, kMax, kGrad>(m, p, x, y, z, n, f, gx, gy, gz);
  else if (K == 3.0f) mappedPointRun<2, kMax, kGrad>(m, p, x, y, z, n, f, gx, gy, gz);
  else if (K == 4.0f) mappedPointRun<3, kMax, kGrad>(m, p, x, y, z, n, f, gx, gy, gz);
  else return false;
  return true;
}

template <bool kMax>
__attribute__((always_inline)) inline bool mappedPoint(const SpaceMap& m, const SkeletalPrimitive& p, const float* x,
                                                       const float* y, const float* z, int n, float* f, float* gx,
                                                       float* gy, float* gz) {
  if (p.skeleton.kind != SkeletonKind::Point || !(p.radius > 0.0f)) return false;
  return gx ? mappedPointStiffness<kMax, true>(m, p, x, y, z, n, f, gx, gy, gz)
            : mappedPointStiffness<kMax, false>(m, p, x, y, z, n, f, gx, gy, gz);
}
}  // namespace


// ------------------------------------------------------------------ evaluation

float FieldEvaluator::evaluatePoint(const FieldProgram& program, const glm::vec3& p, glm::vec3* gradient) {
  if (allFor_ != program.identity() || program.identity() == 0) {
    program.specialiseAll(all_);
    allFor_ = program.identity();
  }
  float f, gx, gy, gz;
  evaluate(program, all_, &p.x, &p.y, &p.z, 1, &f, gradient ? &gx : nullptr, &gy, &gz);
  if (gradient) *gradient = {gx, gy, gz};
  return f;
}

void FieldEvaluator::evaluate(const FieldProgram& program, const ActiveProgram& active, const float* x,
                              const float* y, const float* z, int n, float* f, float* gx, float* gy, float* gz) {
  size_t needStack = size_t(std::max(1, program.maxStack())) * 4 * kChunk;
  if (stack_.size() < needStack) stack_.resize(needStack);
  size_t needCoords = size_t(program.maxMapDepth() + 1) * 3 * kChunk;
  if (coords_.size() < needCoords) coords_.resize(needCoords);
  for (int s = 0; s < n; s += kChunk) {
    int m = std::min(kChunk, n - s);
    runChunk(program, active, x + s, y + s, z + s, m, f + s, gx ? gx + s : nullptr, gx ? gy + s : nullptr,
             gx ? gz + s : nullptr);
  }
}

namespace {

// runChunk's parts. Each is always inlined, so every clone of runChunk (ANIMORPH_KERNEL) compiles
// them for its own instruction set: the same loops and operations in the same order as one body.
#define ANIMORPH_KERNEL_PART __attribute__((always_inline)) inline

// The operand stack over one chunk of n points: entry s holds the values, then (with gradients)
// their x, y, z components, kChunk floats each. Entries known to be +0 everywhere (value and
// gradient) are only flagged in zero[], not filled: a map subtree that reaches none of the points
// pushes one, and a sum skips it (x + 0 is x), so a wide blend of many small mapped primitives
// costs nothing for those away from the points.
struct ChunkStack {
  float* data;
  uint8_t* zero;
  int n;
  bool grad;
  float* F(int s) const { return data + size_t(s) * 4 * kChunk; }
  float* GX(int s) const { return F(s) + kChunk; }
  float* GY(int s) const { return F(s) + 2 * kChunk; }
  float* GZ(int s) const { return F(s) + 3 * kChunk; }
  void fill(int s, float value) const {
    std::fill(F(s), F(s) + n, value);
    if (grad) {
      std::fill(GX(s), GX(s) + n, 0.0f);
      std::fill(GY(s), GY(s) + n, 0.0f);
      std::fill(GZ(s), GZ(s) + n, 0.0f);
    }
  }
  void materialise(int s) const {
    if (!zero[s]) return;
    fill(s, 0.0f);
    zero[s] = 0;
  }
};

ANIMORPH_KERNEL_PART void pointsBox(const float* bx, const float* by, const float* bz, int n, glm::vec3& lo,
                                    glm::vec3& hi) {
  lo = glm::vec3(INFINITY);
  hi = glm::vec3(-INFINITY);
  for (int i = 0; i < n; ++i) {
    lo = glm::min(lo, glm::vec3(bx[i], by[i], bz[i]));
    hi = glm::max(hi, glm::vec3(bx[i], by[i], bz[i]));
  }
}

// The points of one map level in the map's local space (the levels' coordinates never overlap:
// the loops vectorise).
ANIMORPH_KERNEL_PART void mapPoints(const SpaceMap& m, const float* __restrict ix, const float* __restrict iy,
                                    const float* __restrict iz, int n, float* __restrict ox, float* __restrict oy,
                                    float* __restrict oz) {
  if (m.kind == SpaceMapKind::Affine) {
    // The matrix in locals: read through a reference, the stores could alias it and every
    // element would be loaded again per point (a scalar loop); copied, the loop vectorises.
    const glm::mat3 L = m.linear;
    const float l00 = L[0][0], l01 = L[0][1], l02 = L[0][2], l10 = L[1][0], l11 = L[1][1], l12 = L[1][2],
                l20 = L[2][0], l21 = L[2][1], l22 = L[2][2];
    const float o0 = m.origin.x, o1 = m.origin.y, o2 = m.origin.z;
    for (int i = 0; i < n; ++i) {
      float dx = ix[i] - o0, dy = iy[i] - o1, dz = iz[i] - o2;
      ox[i] = l00 * dx + l10 * dy + l20 * dz;
      oy[i] = l01 * dx + l11 * dy + l21 * dz;
      oz[i] = l02 * dx + l12 * dy + l22 * dz;
    }
  } else {
    for (int i = 0; i < n; ++i) {
      glm::vec3 q = m.toLocal({ix[i], iy[i], iz[i]});
      ox[i] = q.x;
      oy[i] = q.y;
      oz[i] = q.z;
    }
  }
}

// The image of the parent box's corners bounds the image of its points (an affine map).
ANIMORPH_KERNEL_PART void affineBox(const SpaceMap& m, const glm::vec3& lo, const glm::vec3& hi, glm::vec3& outLo,
                                    glm::vec3& outHi) {
  glm::vec3 nlo(INFINITY), nhi(-INFINITY);
  for (int c = 0; c < 8; ++c) {
    glm::vec3 q((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    glm::vec3 r = m.linear * (q - m.origin);
    nlo = glm::min(nlo, r);
    nhi = glm::max(nhi, r);
  }
  const glm::vec3 pad = 1e-5f * (nhi - nlo) + 1e-6f * glm::max(glm::abs(nlo), glm::abs(nhi));  // rounding
  outLo = nlo - pad;
  outHi = nhi + pad;
}

// A local gradient mapped back to the parent level: grad_world = J^T grad_local.
ANIMORPH_KERNEL_PART void pullBackGradient(const SpaceMap& m, const float* px, const float* py, const float* pz, int n,
                                           float* gx, float* gy, float* gz) {
  if (m.kind == SpaceMapKind::Affine) {
    const glm::mat3 L = m.linear;  // J = L; grad_world = L^T grad_local (in locals, as in mapPoints)
    const float l00 = L[0][0], l01 = L[0][1], l02 = L[0][2], l10 = L[1][0], l11 = L[1][1], l12 = L[1][2],
                l20 = L[2][0], l21 = L[2][1], l22 = L[2][2];
    for (int i = 0; i < n; ++i) {
      float a = gx[i], b = gy[i], c = gz[i];
      gx[i] = l00 * a + l01 * b + l02 * c;
      gy[i] = l10 * a + l11 * b + l12 * c;
      gz[i] = l20 * a + l21 * b + l22 * c;
    }
  } else {
    for (int i = 0; i < n; ++i) {
      glm::mat3 J;
      m.toLocal({px[i], py[i], pz[i]}, &J);
      glm::vec3 g = glm::transpose(J) * glm::vec3(gx[i], gy[i], gz[i]);
      gx[i] = g.x;
      gy[i] = g.y;
      gz[i] = g.z;
    }
  }
}

// Sum of entries [base, base + cnt) into base. Zero operands add nothing: the first other operand
// is copied (0 + a is a), the others added in their order, as the plain fold would.
ANIMORPH_KERNEL_PART void sumOperands(const ChunkStack& S, int base, int cnt) {
  const int n = S.n;
  int k0 = 0;
  while (k0 < cnt && S.zero[base + k0]) ++k0;
  if (k0 == cnt) {
    S.zero[base] = 1;
    return;
  }
  float* f0 = S.F(base);
  float* gx0 = S.GX(base);
  float* gy0 = S.GY(base);
  float* gz0 = S.GZ(base);
  if (k0 > 0) {
    std::copy(S.F(base + k0), S.F(base + k0) + n, f0);
    if (S.grad) {
      std::copy(S.GX(base + k0), S.GX(base + k0) + n, gx0);
      std::copy(S.GY(base + k0), S.GY(base + k0) + n, gy0);
      std::copy(S.GZ(base + k0), S.GZ(base + k0) + n, gz0);
    }
    S.zero[base] = 0;
  }
  for (int k = k0 + 1; k < cnt; ++k) {
    if (S.zero[base + k]) continue;
    const float* fk = S.F(base + k);
    for (int i = 0; i < n; ++i) f0[i] += fk[i];
    if (S.grad) {
      const float* ax = S.GX(base + k);
      const float* ay = S.GY(base + k);
      const float* az = S.GZ(base + k);
      for (int i = 0; i < n; ++i) {
        gx0[i] += ax[i];
        gy0[i] += ay[i];
        gz0[i] += az[i];
      }
    }
  }
}

// Union (max) or intersection (min) of entries [base, base + cnt); the gradient of the operand taken.
ANIMORPH_KERNEL_PART void maxMinOperands(const ChunkStack& S, int base, int cnt, bool mx) {
  const int n = S.n;
  float* f0 = S.F(base);
  float* gx0 = S.GX(base);
  float* gy0 = S.GY(base);
  float* gz0 = S.GZ(base);
  for (int k = 1; k < cnt; ++k) {
    const float* fk = S.F(base + k);
    if (S.grad) {
      const float* ax = S.GX(base + k);
      const float* ay = S.GY(base + k);
      const float* az = S.GZ(base + k);
      for (int i = 0; i < n; ++i) {
        bool take = mx ? fk[i] > f0[i] : fk[i] < f0[i];
        if (take) {
          f0[i] = fk[i];
          gx0[i] = ax[i];
          gy0[i] = ay[i];
          gz0[i] = az[i];
        }
      }
    } else {
      for (int i = 0; i < n; ++i) f0[i] = mx ? std::max(f0[i], fk[i]) : std::min(f0[i], fk[i]);
    }
  }
}

ANIMORPH_KERNEL_PART void hyperBlendOperands(const ChunkStack& S, int base, int cnt, float q) {
  float vals[64], d[64];
  int m = std::min(cnt, 64);
  for (int i = 0; i < S.n; ++i) {
    for (int k = 0; k < m; ++k) vals[k] = S.F(base + k)[i];
    float h = hyperBlend(vals, m, q, d);
    if (S.grad) {
      float sx = 0, sy = 0, sz = 0;
      for (int k = 0; k < m; ++k) {
        sx += d[k] * S.GX(base + k)[i];
        sy += d[k] * S.GY(base + k)[i];
        sz += d[k] * S.GZ(base + k)[i];
      }
      S.GX(base)[i] = sx;
      S.GY(base)[i] = sy;
      S.GZ(base)[i] = sz;
    }
    S.F(base)[i] = h;
  }
}

ANIMORPH_KERNEL_PART void differenceOperands(const ChunkStack& S, int base, float T) {
  float* f0 = S.F(base);
  const float* f1 = S.F(base + 1);
  for (int i = 0; i < S.n; ++i) {
    float other = 2.0f * T - f1[i];
    if (other < f0[i]) {
      f0[i] = other;
      if (S.grad) {
        S.GX(base)[i] = -S.GX(base + 1)[i];
        S.GY(base)[i] = -S.GY(base + 1)[i];
        S.GZ(base)[i] = -S.GZ(base + 1)[i];
      }
    }
  }
}

ANIMORPH_KERNEL_PART void rFunctionOperands(const ChunkStack& S, int base, float T, bool uni) {
  float* f0 = S.F(base);
  float* gx0 = S.GX(base);
  float* gy0 = S.GY(base);
  float* gz0 = S.GZ(base);
  const float* f1 = S.F(base + 1);
  for (int i = 0; i < S.n; ++i) {
    float d1, d2;
    float r = uni ? rUnion(f0[i] - T, f1[i] - T, d1, d2) : rIntersection(f0[i] - T, f1[i] - T, d1, d2);
    f0[i] = T + r;
    if (S.grad) {
      gx0[i] = d1 * gx0[i] + d2 * S.GX(base + 1)[i];
      gy0[i] = d1 * gy0[i] + d2 * S.GY(base + 1)[i];
      gz0[i] = d1 * gz0[i] + d2 * S.GZ(base + 1)[i];
    }
  }
}

ANIMORPH_KERNEL_PART void boundedBlendOperands(const ChunkStack& S, int base, float T, const float* prm) {
  BoundedBlendParams bp{prm[0], prm[1], prm[2], prm[3]};
  float* f0 = S.F(base);
  float* gx0 = S.GX(base);
  float* gy0 = S.GY(base);
  float* gz0 = S.GZ(base);
  const float* f1 = S.F(base + 1);
  const float* f2 = S.F(base + 2);
  for (int i = 0; i < S.n; ++i) {
    float d[3];
    float r = boundedBlend(f0[i] - T, f1[i] - T, f2[i] - T, bp, d);
    f0[i] = T + r;
    if (S.grad) {
      gx0[i] = d[0] * gx0[i] + d[1] * S.GX(base + 1)[i] + d[2] * S.GX(base + 2)[i];
      gy0[i] = d[0] * gy0[i] + d[1] * S.GY(base + 1)[i] + d[2] * S.GY(base + 2)[i];
      gz0[i] = d[0] * gz0[i] + d[1] * S.GZ(base + 1)[i] + d[2] * S.GZ(base + 2)[i];
    }
  }
}

ANIMORPH_KERNEL_PART void remapOperand(const ChunkStack& S, int base, float T, const float* prm) {
  float* f0 = S.F(base);
  float* gx0 = S.GX(base);
  float* gy0 = S.GY(base);
  float* gz0 = S.GZ(base);
  for (int i = 0; i < S.n; ++i) {
    float d;
    f0[i] = remapPotential(f0[i], prm[0], prm[1], T, d);
    if (S.grad) {
      gx0[i] *= d;
      gy0[i] *= d;
      gz0[i] *= d;
    }
  }
}

// A combining op over the top op.count entries, leaving its result in the first of them.
ANIMORPH_KERNEL_PART void combineOperands(const ChunkStack& S, const FieldOp& op, int base, const float* prm, float T) {
  const int cnt = int(op.count);
  if (op.code == OpCode::Sum) {
    sumOperands(S, base, cnt);
    return;
  }
  for (int k = 0; k < cnt; ++k) S.materialise(base + k);
  switch (op.code) {
    case OpCode::Max:
    case OpCode::Min: maxMinOperands(S, base, cnt, op.code == OpCode::Max); break;
    case OpCode::HyperBlend: hyperBlendOperands(S, base, cnt, prm[0]); break;
    case OpCode::Difference: differenceOperands(S, base, T); break;
    case OpCode::RUnion:
    case OpCode::RIntersection: rFunctionOperands(S, base, T, op.code == OpCode::RUnion); break;
    case OpCode::BoundedBlend: boundedBlendOperands(S, base, T, prm); break;
    case OpCode::Remap: remapOperand(S, base, T, prm); break;
    default: break;
  }
}

// The points of a chunk at each map level: their coordinates and box (skeletal primitives are
// skipped against it); level 0 holds the chunk's own points.
struct ChunkLevels {
  const float** cx;
  const float** cy;
  const float** cz;
  glm::vec3* boxes;  // lo, hi per level
  float* coords;     // the mapped levels' coordinates, 3 * kChunk floats per level above 0
  int level = 0;
};

// A Prims op: its primitives' field (and gradient) at the current level, pushed at sp.
ANIMORPH_KERNEL_PART void primsOp(const FieldProgram& P, const ActiveProgram& A, const FieldOp& op,
                                  const ChunkStack& S, int sp, const ChunkLevels& L, float T) {
  const int n = S.n, level = L.level;
  S.fill(sp, 0.0f);
  S.zero[sp] = 0;
  const uint32_t* idx = A.indices.data() + op.first;
  float* f = S.F(sp);
  float* gx = S.grad ? S.GX(sp) : nullptr;
  float* gy = S.grad ? S.GY(sp) : nullptr;
  float* gz = S.grad ? S.GZ(sp) : nullptr;
  switch (op.primClass) {
    case PrimClass::Convolution:
      convolutionKernel(P.convolution, idx, int(op.count), L.cx[level], L.cy[level], L.cz[level], n, f, gx, gy, gz);
      break;
    case PrimClass::Skeletal:
      skeletalKernel(P, idx, int(op.count), op.combineMax, L.cx[level], L.cy[level], L.cz[level], n,
                     L.boxes[2 * level], L.boxes[2 * level + 1], f, gx, gy, gz);
      break;
    case PrimClass::Capsule:
      capsuleKernel(P.capsules, T, idx, int(op.count), op.combineMax, L.cx[level], L.cy[level], L.cz[level], n, f,
                    gx, gy, gz);
      break;
  }
}

// A BeginMap at opIndex followed by one skeletal point primitive and its EndMap, under an affine
// map (a meta-primitive's instance): evaluated in one loop into sp. False when the ops are not of
// that form or the map cannot be fused (then nothing is written).
ANIMORPH_KERNEL_PART bool fusedMappedPoint(const FieldProgram& P, const ActiveProgram& A, size_t opIndex,
                                           const ChunkStack& S, int sp, const ChunkLevels& L) {
  const SpaceMap& m = P.maps[A.ops[opIndex].first];
  if (m.kind != SpaceMapKind::Affine || opIndex + 2 >= A.ops.size()) return false;
  const FieldOp& prims = A.ops[opIndex + 1];
  if (prims.code != OpCode::Prims || prims.primClass != PrimClass::Skeletal || prims.count != 1 ||
      A.ops[opIndex + 2].code != OpCode::EndMap)
    return false;
  const SkeletalPrimitive& p = P.skeletal[A.indices[prims.first]];
  const int n = S.n, level = L.level;
  float* gx = S.grad ? S.GX(sp) : nullptr;
  float* gy = S.grad ? S.GY(sp) : nullptr;
  float* gz = S.grad ? S.GZ(sp) : nullptr;
  return prims.combineMax ? mappedPoint<true>(m, p, L.cx[level], L.cy[level], L.cz[level], n, S.F(sp), gx, gy, gz)
                          : mappedPoint<false>(m, p, L.cx[level], L.cy[level], L.cz[level], n, S.F(sp), gx, gy, gz);
}

// A BeginMap: the current level's points mapped into the next level, with their box.
ANIMORPH_KERNEL_PART void enterMapLevel(const SpaceMap& m, int n, ChunkLevels& L) {
  const int level = L.level;
  float* out = L.coords + size_t(level + 1) * 3 * kChunk;
  mapPoints(m, L.cx[level], L.cy[level], L.cz[level], n, out, out + kChunk, out + 2 * kChunk);
  L.level = level + 1;
  L.cx[level + 1] = out;
  L.cy[level + 1] = out + kChunk;
  L.cz[level + 1] = out + 2 * kChunk;
  glm::vec3* boxes = L.boxes;
  if (m.kind == SpaceMapKind::Affine)
    affineBox(m, boxes[2 * level], boxes[2 * level + 1], boxes[2 * level + 2], boxes[2 * level + 3]);
  else
    pointsBox(L.cx[level + 1], L.cy[level + 1], L.cz[level + 1], n, boxes[2 * level + 2], boxes[2 * level + 3]);
}

}  // namespace

// Cloned for wider vectors (its map, sum and fill loops run over the whole run of points); this
// file does not contract products into FMAs, so each clone computes the same values. An
// interpreter over the active program's ops: the stack, the map levels and their boxes live here,
// the ops' loops in the always-inlined parts above (each clone stays one function: splitting the
// ops out into those parts changed neither the clones' sizes by more than 2 % nor the time of a
// one-thread polygonisation of the dinosaur demo at 128^3 measurably).
ANIMORPH_KERNEL
void FieldEvaluator::runChunk(const FieldProgram& P, const ActiveProgram& A, const float* x, const float* y,
                              const float* z, int n, float* fOut, float* gxOut, float* gyOut, float* gzOut) {
  const bool grad = gxOut != nullptr;
  const float T = P.threshold;
  int sp = 0;  // stack size
  levels_.resize(size_t(P.maxMapDepth() + 1) * 3);
  levelBoxes_.resize(size_t(P.maxMapDepth() + 1) * 2);
  ChunkLevels L{levels_.data(), levels_.data() + P.maxMapDepth() + 1, levels_.data() + 2 * (P.maxMapDepth() + 1),
                levelBoxes_.data(), coords_.data()};
  L.cx[0] = x;
  L.cy[0] = y;
  L.cz[0] = z;
  pointsBox(x, y, z, n, L.boxes[0], L.boxes[1]);
  thread_local std::vector<uint8_t> zeroSlots;
  zeroSlots.assign(size_t(std::max(1, P.maxStack())) + 1, 0);
  const ChunkStack S{stack_.data(), zeroSlots.data(), n, grad};
  uint8_t* zero = S.zero;
  auto pushConstant = [&](float value) {
    zero[sp] = value == 0.0f && !std::signbit(value);
    if (!zero[sp]) S.fill(sp, value);
    ++sp;
  };
  const glm::vec3 worldLo = L.boxes[0], worldHi = L.boxes[1];
  for (size_t opIndex = 0; opIndex < A.ops.size(); ++opIndex) {
    const FieldOp& op = A.ops[opIndex];
    if (op.code == OpCode::BeginMap) {
      // A map whose primitives reach none of the points: its subtree has its empty value there.
      const Bounds& r = P.mapReach(op.first);
      if (r.empty() || glm::any(glm::greaterThan(r.min, worldHi)) || glm::any(glm::lessThan(r.max, worldLo))) {
        int open = 1;
        while (open > 0) {
          const OpCode c = A.ops[++opIndex].code;
          open += c == OpCode::BeginMap ? 1 : c == OpCode::EndMap ? -1 : 0;
        }
        pushConstant(A.ops[opIndex].emptyValue);
        continue;
      }
    }
    switch (op.code) {
      case OpCode::Prims:
        primsOp(P, A, op, S, sp, L, T);
        ++sp;
        break;
      case OpCode::Const: pushConstant(op.emptyValue); break;
      case OpCode::BeginMap:
        if (fusedMappedPoint(P, A, opIndex, S, sp, L)) {
          zero[sp] = 0;
          ++sp;
          opIndex += 2;
        } else {
          enterMapLevel(P.maps[op.first], n, L);
        }
        break;
      case OpCode::EndMap:
        --L.level;
        if (grad && !zero[sp - 1])  // a zero gradient stays zero
          pullBackGradient(P.maps[op.first], L.cx[L.level], L.cy[L.level], L.cz[L.level], n, S.GX(sp - 1),
                           S.GY(sp - 1), S.GZ(sp - 1));
        break;
      default: {
        const int base = sp - int(op.count);
        combineOperands(S, op, base, P.params.data() + op.param, T);
        sp = base + 1;
      }
    }
  }
  S.materialise(0);
  const float* f = S.F(0);
  for (int i = 0; i < n; ++i) fOut[i] = f[i] - T;
  if (grad) {
    std::copy(S.GX(0), S.GX(0) + n, gxOut);
    std::copy(S.GY(0), S.GY(0) + n, gyOut);
    std::copy(S.GZ(0), S.GZ(0) + n, gzOut);
  }
}

}  // namespace animorph
