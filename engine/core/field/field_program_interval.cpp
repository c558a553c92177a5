// FieldProgram, part 3 of 4: bounds of the field over a region (interval arithmetic), which let
// the polygoniser skip regions of one sign.
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

using field_detail::boxesOverlap;
using field_detail::distToSegment;

// ------------------------------------------------------------------ intervals

Bounds FieldProgram::tightBounds(int depth) const {
  if (unbounded_ || bounds_.empty()) return bounds_;
  Bounds out;
  ActiveProgram active;
  std::vector<uint32_t> reaching;
  // Per level: the primitives whose box overlaps that level's current box. A child box lies inside
  // its parent's (its corners are the parent's or the parent's centre), so its primitives are among
  // the parent's: each box tests only those, with the same result as testing every primitive.
  std::vector<std::vector<uint32_t>> overlapping(size_t(std::max(depth, 0) + 1));
  // Depth-first over the octree of bounds(), children visited from the last to the first.
  std::function<void(const Bounds&, int)> visit = [&](const Bounds& box, int level) {
    // A box inside the bounds found so far cannot grow them, whatever its leaves: skip it (the
    // result is the same; the preview computes these bounds every frame of a morph).
    if (!out.empty() && glm::all(glm::greaterThanEqual(box.min, out.min)) &&
        glm::all(glm::lessThanEqual(box.max, out.max)))
      return;
    std::vector<uint32_t>& mine = overlapping[size_t(std::min(level, depth))];
    const std::vector<uint32_t>* parent = level > 0 ? &overlapping[size_t(level - 1)] : nullptr;
    mine.clear();
    auto keep = [&](uint32_t g) {
      if (boxesOverlap(primitiveBounds[g].box, box)) mine.push_back(g);
    };
    if (parent) {
      for (uint32_t g : *parent) keep(g);
    } else {
      for (uint32_t g = 0; g < primitiveBounds.size(); ++g) keep(g);
    }
    primitivesReaching(box, reaching, &mine);
    specialise(reaching, active);
    Interval iv = interval(active, box.center(), 0.5f * box.diagonal());
    if (iv.hi < 0.0f) return;
    if (level >= depth || iv.lo >= 0.0f) {
      out.add(box);
      return;
    }
    glm::vec3 c = box.center();
    for (int k = 7; k >= 0; --k) {
      Bounds child;
      child.add(glm::vec3(k & 1 ? c.x : box.min.x, k & 2 ? c.y : box.min.y, k & 4 ? c.z : box.min.z));
      child.add(glm::vec3(k & 1 ? box.max.x : c.x, k & 2 ? box.max.y : c.y, k & 4 ? box.max.z : c.z));
      visit(child, level + 1);
    }
  };
  visit(bounds_, 0);
  return out;
}

namespace {

float potentialAt(float d, float R, float I, float k) {
  float gf;
  return skeletalPotential(d * d, R, I, k, gf);
}

// The interval of a union (max) of triangle primitives sharing radius R, intensity I > 0 and an
// integer stiffness: each triangle gives [g(d + rho), g(max(0, d - rho))] for its distance d to
// the centre, both non-increasing in d as computed in float, so the union's interval is the one of
// the smallest d, and a triangle whose enclosing ball (centroid, reach - R) is no nearer than the
// smallest d so far (with a margin far above float rounding) cannot change it. The same interval
// as the plain loop, with the exact distance of only the triangles near the centre. False: not
// such a union.
bool triangleUnionInterval(const FieldProgram& P, const uint32_t* idx, uint32_t count, const glm::vec3& c, float rho,
                           Interval& out) {
  if (count < 2) return false;
  const SkeletalPrimitive& first = P.skeletal[idx[0]];
  const float R = first.radius, I = first.intensity, K = first.stiffness;
  if (!(R > 0.0f) || !(I > 0.0f) || !(K >= 0.0f && K <= 8.0f && float(int(K)) == K)) return false;
  thread_local std::vector<float> nearBound;
  nearBound.resize(count);
  float ballMax = 0.0f, nearest = INFINITY;
  uint32_t nearestK = 0;
  for (uint32_t k = 0; k < count; ++k) {
    const SkeletalPrimitive& p = P.skeletal[idx[k]];
    const SkeletalReach& bound = P.skeletalReach[idx[k]];
    if (p.skeleton.kind != SkeletonKind::Triangle || p.radius != R || p.intensity != I || p.stiffness != K ||
        bound.a != bound.b)
      return false;
    const float ball = std::max(0.0f, bound.reach - R);
    ballMax = std::max(ballMax, ball);
    nearBound[k] = glm::length(c - bound.a) - ball;
    if (!std::isfinite(nearBound[k])) return false;
    if (nearBound[k] < nearest) {
      nearest = nearBound[k];
      nearestK = k;
    }
  }
  const float margin = 1e-5f * (std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) + R + ballMax);
  auto distance = [&](uint32_t k) { return glm::length(c - closestOnSkeleton(P.skeletal[idx[k]].skeleton, c)); };
  float d = distance(nearestK);  // the likely nearest first: the others then mostly fall to the ball test
  for (uint32_t k = 0; k < count; ++k)
    if (k != nearestK && nearBound[k] - margin < d) d = std::min(d, distance(k));
  const float g0 = potentialAt(std::max(0.0f, d - rho), R, I, K);
  const float g1 = potentialAt(d + rho, R, I, K);
  out = {std::max(0.0f, std::min(g0, g1)), std::max(0.0f, std::max(g0, g1))};
  return true;
}

// The interval of one Prims op's primitives over the ball (c, rho), combined by sum or max.
inline Interval primsInterval(const FieldProgram& P, const ActiveProgram& prog, const FieldOp& op, glm::vec3 c,
                              float rho) {
  Interval acc{0.0f, 0.0f};
  if (op.primClass == PrimClass::Convolution) {
    thread_local std::vector<float> los, his;
    los.resize(op.count);
    his.resize(op.count);
    convolutionIntervalKernel(P.convolution, prog.indices.data() + op.first, int(op.count), c, rho, los.data(),
                              his.data());
    for (uint32_t k = 0; k < op.count; ++k) {
      acc.lo += los[k];
      acc.hi += his[k];
    }
    return acc;
  }
  if (op.primClass == PrimClass::Skeletal && op.combineMax &&
      triangleUnionInterval(P, prog.indices.data() + op.first, op.count, c, rho, acc))
    return acc;
  const float T = P.threshold;
  for (uint32_t k = 0; k < op.count; ++k) {
    uint32_t i = prog.indices[op.first + k];
    Interval v{0.0f, 0.0f};
    if (op.primClass == PrimClass::Skeletal) {
      const SkeletalPrimitive& p = P.skeletal[i];
      // A point (most primitives: meta-primitives' instances) without the call and the copy.
      glm::vec3 closest = p.skeleton.p0;
      if (p.skeleton.kind != SkeletonKind::Point) {
        Skeleton s = p.skeleton;
        if (s.kind == SkeletonKind::Curve) s.curve = P.curvePoints.data() + p.curveFirst;
        closest = closestOnSkeleton(s, c);
      }
      float d = glm::length(c - closest);
      float g0 = potentialAt(std::max(0.0f, d - rho), p.radius, p.intensity, p.stiffness);
      float g1 = potentialAt(d + rho, p.radius, p.intensity, p.stiffness);
      v = {std::min(g0, g1), std::max(g0, g1)};
    } else {
      const CapsulePrimitive& cp = P.capsules[i];
      float d = distToSegment(c, cp.a, cp.b);
      auto pot = [&](float dd) { return cp.radius > 0.0f ? T * std::max(0.0f, 2.0f - dd / cp.radius) : 0.0f; };
      v = {pot(d + rho), pot(std::max(0.0f, d - rho))};
    }
    if (op.combineMax) acc = {std::max(acc.lo, v.lo), std::max(acc.hi, v.hi)};
    else acc = {acc.lo + v.lo, acc.hi + v.hi};
  }
  return acc;
}

// A BeginMap op: the ball (c, rho) into the map's local space (the radius grown by the map's
// stretch bound over the ball; an affine map's bound is cached per program and map).
inline void enterMapBall(const FieldProgram& P, const FieldOp& op, glm::vec3& c, float& rho) {
  thread_local std::vector<float> affineStretch;  // per map of the program below (-1: not yet)
  thread_local uint64_t affineStretchFor = 0;
  const SpaceMap& m = P.maps[op.first];
  float stretch;
  if (m.kind == SpaceMapKind::Affine && P.identity() != 0) {
    // An affine map's bound does not depend on the ball: computed once per program and map.
    if (affineStretchFor != P.identity() || affineStretch.size() != P.maps.size()) {
      affineStretch.assign(P.maps.size(), -1.0f);
      affineStretchFor = P.identity();
    }
    float& cached = affineStretch[op.first];
    if (cached < 0.0f) cached = m.localStretchBound(c, rho);
    stretch = cached;
  } else {
    stretch = m.localStretchBound(c, rho);
  }
  c = m.kind == SpaceMapKind::Affine ? m.linear * (c - m.origin) : m.toLocal(c);  // toLocal's own affine case
  rho = std::isinf(stretch) ? INFINITY : rho * stretch * 1.0001f;
}

// A combining op (Sum, Max, Min, blends, Difference, Remap) over the intervals of its n operands
// st[base..base+n): the interval of its result (NaN ends widened to infinity).
inline Interval combineIntervals(const FieldOp& op, const float* prm, float T, const std::vector<Interval>& st,
                                 size_t base) {
  const uint32_t n = op.count;
  Interval r;
  switch (op.code) {
    case OpCode::Sum:
      r = {0.0f, 0.0f};
      for (uint32_t k = 0; k < n; ++k) r = {r.lo + st[base + k].lo, r.hi + st[base + k].hi};
      break;
    case OpCode::Max:
      r = st[base];
      for (uint32_t k = 1; k < n; ++k) r = {std::max(r.lo, st[base + k].lo), std::max(r.hi, st[base + k].hi)};
      break;
    case OpCode::Min:
      r = st[base];
      for (uint32_t k = 1; k < n; ++k) r = {std::min(r.lo, st[base + k].lo), std::min(r.hi, st[base + k].hi)};
      break;
    case OpCode::HyperBlend: {
      float los[64], his[64], d[64];
      uint32_t m = std::min<uint32_t>(n, 64);
      for (uint32_t k = 0; k < m; ++k) {
        los[k] = std::max(0.0f, st[base + k].lo);
        his[k] = std::max(0.0f, st[base + k].hi);
      }
      r = {hyperBlend(los, int(m), prm[0], d), hyperBlend(his, int(m), prm[0], d)};
      break;
    }
    case OpCode::Difference:
      r = {std::min(st[base].lo, 2.0f * T - st[base + 1].hi), std::min(st[base].hi, 2.0f * T - st[base + 1].lo)};
      break;
    case OpCode::RUnion:
    case OpCode::RIntersection: {
      float d1, d2;
      auto f = [&](float a, float b) {
        return op.code == OpCode::RUnion ? rUnion(a - T, b - T, d1, d2) : rIntersection(a - T, b - T, d1, d2);
      };
      r = {T + f(st[base].lo, st[base + 1].lo), T + f(st[base].hi, st[base + 1].hi)};
      break;
    }
    case OpCode::BoundedBlend: {
      float d1, d2;
      float a0 = prm[0];
      r = {T + rUnion(st[base].lo - T, st[base + 1].lo - T, d1, d2) + std::min(0.0f, a0),
           T + rUnion(st[base].hi - T, st[base + 1].hi - T, d1, d2) + std::max(0.0f, a0)};
      break;
    }
    case OpCode::Remap: {  // monotone in p; a negative scale swaps the ends
      float d;
      const float a = remapPotential(st[base].lo, prm[0], prm[1], T, d);
      const float b = remapPotential(st[base].hi, prm[0], prm[1], T, d);
      r = {std::min(a, b), std::max(a, b)};
      break;
    }
    default: r = {-INFINITY, INFINITY};
  }
  if (std::isnan(r.lo)) r.lo = -INFINITY;
  if (std::isnan(r.hi)) r.hi = INFINITY;
  return r;
}

}  // namespace

Interval FieldProgram::interval(const ActiveProgram& prog, const glm::vec3& centre, float radius) const {
  thread_local std::vector<Interval> st;
  thread_local std::vector<glm::vec4> balls;
  st.clear();
  balls.clear();
  glm::vec3 c = centre;
  float rho = radius;
  const float T = threshold;
  for (const FieldOp& op : prog.ops) {
    switch (op.code) {
      case OpCode::Prims: st.push_back(primsInterval(*this, prog, op, c, rho)); break;
      case OpCode::Const: st.push_back({op.emptyValue, op.emptyValue}); break;
      case OpCode::BeginMap:
        balls.push_back(glm::vec4(c, rho));
        enterMapBall(*this, op, c, rho);
        break;
      case OpCode::EndMap: {
        c = glm::vec3(balls.back());
        rho = balls.back().w;
        balls.pop_back();
        break;
      }
      default: {
        const size_t base = st.size() - op.count;
        const Interval r = combineIntervals(op, params.data() + op.param, T, st, base);
        st.resize(base + 1);
        st[base] = r;
      }
    }
  }
  if (st.empty()) return {-T, -T};
  return {st.back().lo - T, st.back().hi - T};
}

}  // namespace animorph
