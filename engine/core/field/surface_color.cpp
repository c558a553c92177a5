#include "core/field/surface_color.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/field/operators.h"

namespace animorph {

namespace {

constexpr int kRun = 128;  // points evaluated together (one specialised program per run)

// One run's operand stack: entry s holds kRun values, then kRun each of r, g, b; the map levels'
// points; a scratch row for one primitive's contribution and one for the weights.
struct RunScratch {
  std::vector<float> stack, coords, one, weight;
  std::vector<uint32_t> reach;
  ActiveProgram active;
  std::vector<const float*> lx, ly, lz;  // per map level: the points
  std::vector<glm::vec3> lo, hi;         // per map level: their box
  float* V(int s) { return stack.data() + size_t(s) * 4 * kRun; }
  float* C(int s, int c) { return V(s) + size_t(c + 1) * kRun; }
};

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

// One primitive's contribution at the points into S.one.
void contribution(const FieldProgram& P, PrimClass cls, const uint32_t* idx, bool combineMax, const float* x,
                  const float* y, const float* z, int n, const glm::vec3& lo, const glm::vec3& hi, float* f) {
  std::fill(f, f + n, 0.0f);
  switch (cls) {
    case PrimClass::Skeletal: skeletalKernel(P, idx, 1, combineMax, x, y, z, n, lo, hi, f, nullptr, nullptr, nullptr); break;
    case PrimClass::Convolution: convolutionKernel(P.convolution, idx, 1, x, y, z, n, f, nullptr, nullptr, nullptr); break;
    case PrimClass::Capsule:
      capsuleKernel(P.capsules, P.threshold, idx, 1, combineMax, x, y, z, n, f, nullptr, nullptr, nullptr);
      break;
  }
}

// A Prims op into entry s: the sum (weighted colours) or max (the larger's colour) of its primitives.
void primsOp(const FieldProgram& P, const ActiveProgram& A, const FieldOp& op, RunScratch& S, int s, const float* x,
             const float* y, const float* z, int n, const glm::vec3& lo, const glm::vec3& hi) {
  float* V = S.V(s);
  float* R = S.C(s, 0);
  float* G = S.C(s, 1);
  float* B = S.C(s, 2);
  float* W = S.weight.data();
  float* one = S.one.data();
  std::fill(V, V + n, 0.0f);
  std::fill(W, W + n, 0.0f);
  const glm::vec3 first = P.primitiveColor(op.primClass, A.indices[op.first]);
  if (op.combineMax) fillColor(S, s, n, first);
  else
    for (int k = 0; k < 3; ++k) std::fill(S.C(s, k), S.C(s, k) + n, 0.0f);
  for (uint32_t k = 0; k < op.count; ++k) {
    const uint32_t* idx = A.indices.data() + op.first + k;
    const glm::vec3 c = P.primitiveColor(op.primClass, *idx);
    contribution(P, op.primClass, idx, op.combineMax, x, y, z, n, lo, hi, one);
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

// Entry base's colour at point i: the blend of entries base + k with weights w[k] (first kept when all 0).
void weighted(RunScratch& S, int base, int count, int i, const float* w) {
  float sum = 0.0f;
  glm::vec3 c(0.0f);
  for (int k = 0; k < count; ++k) {
    if (!(w[k] > 0.0f)) continue;
    sum += w[k];
    c += w[k] * glm::vec3(S.C(base + k, 0)[i], S.C(base + k, 1)[i], S.C(base + k, 2)[i]);
  }
  if (!(sum > 0.0f)) return;
  c /= sum;
  S.C(base, 0)[i] = c.r;
  S.C(base, 1)[i] = c.g;
  S.C(base, 2)[i] = c.b;
}

void take(RunScratch& S, int base, int k, int i) {
  for (int c = 0; c < 3; ++c) S.C(base, c)[i] = S.C(base + k, c)[i];
}

// A combining op over entries [base, base + count), result (value and colour) in entry base.
void combine(const FieldProgram& P, const FieldOp& op, RunScratch& S, int base, int n) {
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
        weighted(S, base, std::min(count, 64), i, w);
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
        break;
      }
      case OpCode::Difference: V0[i] = std::min(V0[i], 2.0f * T - S.V(base + 1)[i]); break;  // the kept side's colour
      case OpCode::RUnion:
      case OpCode::RIntersection: {
        float d1, d2;
        const float s1 = V0[i] - T, s2 = S.V(base + 1)[i] - T;
        const float r = op.code == OpCode::RUnion ? rUnion(s1, s2, d1, d2) : rIntersection(s1, s2, d1, d2);
        w[0] = d1;
        w[1] = d2;
        weighted(S, base, 2, i, w);
        V0[i] = T + r;
        break;
      }
      case OpCode::BoundedBlend: {
        const float r = boundedBlend(V0[i] - T, S.V(base + 1)[i] - T, S.V(base + 2)[i] - T,
                                     BoundedBlendParams{prm[0], prm[1], prm[2], prm[3]}, d);
        weighted(S, base, 2, i, d);  // the bounding solid gives no colour
        V0[i] = T + r;
        break;
      }
      case OpCode::Remap: {
        float dd;
        V0[i] = remapPotential(V0[i], prm[0], prm[1], T, dd);
        break;
      }
      default: break;
    }
  }
}

// The ops of a specialised program over one run of n points (n <= kRun): colours into out.
void runColors(const FieldProgram& P, const ActiveProgram& A, RunScratch& S, const float* x, const float* y,
               const float* z, int n, glm::vec4* out) {
  const int depth = P.maxMapDepth() + 1;
  S.stack.resize(size_t(std::max(1, P.maxStack())) * 4 * kRun);
  S.coords.resize(size_t(depth) * 3 * kRun);
  S.one.resize(kRun);
  S.weight.resize(kRun);
  for (auto* l : {&S.lx, &S.ly, &S.lz}) l->resize(size_t(depth));
  S.lo.resize(size_t(depth));
  S.hi.resize(size_t(depth));
  std::vector<const float*>&lx = S.lx, &ly = S.ly, &lz = S.lz;
  std::vector<glm::vec3>&lo = S.lo, &hi = S.hi;
  lx[0] = x;
  ly[0] = y;
  lz[0] = z;
  boxOf(x, y, z, n, lo[0], hi[0]);
  const glm::vec3 clay = srgbToLinear(kClayColorSrgb);
  int sp = 0, level = 0;
  for (const FieldOp& op : A.ops) {
    switch (op.code) {
      case OpCode::Prims:
        primsOp(P, A, op, S, sp, lx[size_t(level)], ly[size_t(level)], lz[size_t(level)], n, lo[size_t(level)],
                hi[size_t(level)]);
        ++sp;
        break;
      case OpCode::Const:
        std::fill(S.V(sp), S.V(sp) + n, op.emptyValue);
        fillColor(S, sp, n, clay);
        ++sp;
        break;
      case OpCode::BeginMap: {
        const SpaceMap& m = P.maps[op.first];
        float* o = S.coords.data() + size_t(level + 1) * 3 * kRun;
        for (int i = 0; i < n; ++i) {
          const glm::vec3 q = m.toLocal({lx[size_t(level)][i], ly[size_t(level)][i], lz[size_t(level)][i]});
          o[i] = q.x;
          o[kRun + i] = q.y;
          o[2 * kRun + i] = q.z;
        }
        ++level;
        lx[size_t(level)] = o;
        ly[size_t(level)] = o + kRun;
        lz[size_t(level)] = o + 2 * kRun;
        boxOf(o, o + kRun, o + 2 * kRun, n, lo[size_t(level)], hi[size_t(level)]);
        break;
      }
      case OpCode::EndMap: --level; break;
      default: {
        const int base = sp - int(op.count);
        combine(P, op, S, base, n);
        sp = base + 1;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    glm::vec3 c = sp > 0 ? glm::vec3(S.C(0, 0)[i], S.C(0, 1)[i], S.C(0, 2)[i]) : clay;
    out[i] = glm::vec4(glm::clamp(c, 0.0f, 1.0f), 1.0f);
  }
}

// Points order[begin, end) (at most kRun): evaluated with the primitives reaching their box.
void evaluateRun(const FieldProgram& P, const glm::vec3* points, const uint32_t* order, int n, glm::vec4* out,
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
  P.primitivesReaching(box, S.reach);
  P.specialise(S.reach, S.active);
  glm::vec4 colors[kRun];
  runColors(P, S.active, S, xyz, xyz + kRun, xyz + 2 * kRun, n, colors);
  for (int i = 0; i < n; ++i) out[order[i]] = colors[i];
}

}  // namespace

void SurfaceColorEvaluator::evaluate(const FieldProgram& program, const glm::vec3* points, size_t n, glm::vec4* out,
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

glm::vec3 SurfaceColorEvaluator::evaluatePoint(const FieldProgram& program, const glm::vec3& p) {
  glm::vec4 c;
  evaluate(program, &p, 1, &c, 1);
  return glm::vec3(c);
}

}  // namespace animorph
