#include "core/poly/program_change.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace animorph {

namespace {

constexpr float kUnbounded = std::numeric_limits<float>::infinity();

bool sameMap(const SpaceMap& a, const SpaceMap& b) {
  return a.kind == b.kind && a.linear == b.linear && a.origin == b.origin && a.forwardLinear == b.forwardLinear &&
         a.length == b.length && a.k0 == b.k0 && a.k1 == b.k1;
}

bool samePrimitive(const FieldProgram& a, const FieldProgram& b, PrimClass cls, uint32_t i) {
  switch (cls) {
    case PrimClass::Skeletal: {
      const SkeletalPrimitive &p = a.skeletal[i], &q = b.skeletal[i];
      const Skeleton &s = p.skeleton, &t = q.skeleton;
      if (s.kind != t.kind || s.p0 != t.p0 || s.p1 != t.p1 || s.p2 != t.p2 || s.r0 != t.r0 || s.r1 != t.r1 ||
          s.curveCount != t.curveCount || p.curveFirst != q.curveFirst || p.radius != q.radius ||
          p.intensity != q.intensity || p.stiffness != q.stiffness)
        return false;
      const SkeletalReach &r = a.skeletalReach[i], &u = b.skeletalReach[i];
      if (r.a != u.a || r.b != u.b || r.reach != u.reach) return false;
      if (s.kind == SkeletonKind::Curve)
        for (int k = 0; k < s.curveCount; ++k)
          if (a.curvePoints[p.curveFirst + uint32_t(k)] != b.curvePoints[p.curveFirst + uint32_t(k)]) return false;
      return true;
    }
    case PrimClass::Convolution: {
      const ConvolutionData &c = a.convolution, &d = b.convolution;
      return c.bx[i] == d.bx[i] && c.by[i] == d.by[i] && c.bz[i] == d.bz[i] && c.ax[i] == d.ax[i] &&
             c.ay[i] == d.ay[i] && c.az[i] == d.az[i] && c.length[i] == d.length[i] && c.weight[i] == d.weight[i] &&
             c.sharpness[i] == d.sharpness[i] && c.cut2[i] == d.cut2[i];
    }
    case PrimClass::Capsule: {
      const CapsulePrimitive &c = a.capsules[i], &d = b.capsules[i];
      return c.a == d.a && c.b == d.b && c.radius == d.radius;
    }
  }
  return false;
}

// Child -> world transform of the affine maps above a primitive: x = origin + linear * c.
struct Placement {
  glm::mat3 linear{1.0f};
  glm::vec3 origin{0.0f};
  float scale = 1.0f;    // linear = scale * rotation
  bool similar = true;   // every map above is affine and linear a similarity (distances scale by `scale`)
};

Placement compose(const Placement& outer, const SpaceMap& m) {
  Placement r;
  r.similar = outer.similar && m.kind == SpaceMapKind::Affine;
  if (!r.similar) return r;
  r.origin = outer.origin + outer.linear * m.origin;
  r.linear = outer.linear * m.forwardLinear;
  // A similarity has orthogonal columns of one length.
  const glm::vec3 c0 = r.linear[0], c1 = r.linear[1], c2 = r.linear[2];
  const float l0 = glm::length(c0), l1 = glm::length(c1), l2 = glm::length(c2);
  const float tol = 1e-5f * std::max({l0, l1, l2});
  r.similar = std::abs(l0 - l1) <= tol && std::abs(l0 - l2) <= tol && std::abs(glm::dot(c0, c1)) <= tol * l0 &&
              std::abs(glm::dot(c0, c2)) <= tol * l0 && std::abs(glm::dot(c1, c2)) <= tol * l0 && l0 > 0.0f;
  r.scale = l0;
  return r;
}

// Where a primitive sits: whether any map above it changed, and its placement in both frames.
struct Context {
  bool mapChanged = false;
  Placement now, prev;
};

// Calls fn(op, global id, class-local index, context) for every primitive of every Prims op.
template <class Fn>
void forEachPrimitive(const FieldProgram& now, const FieldProgram& prev, Fn&& fn) {
  struct Open {
    bool changed;
    Placement now, prev;
  };
  std::vector<Open> open;
  int openChanged = 0;
  Context ctx;
  for (const FieldOp& op : now.ops) {
    if (op.code == OpCode::BeginMap) {
      const SpaceMap &m = now.maps[op.first], &n = prev.maps[op.first];
      const Placement outerNow = open.empty() ? Placement{} : open.back().now;
      const Placement outerPrev = open.empty() ? Placement{} : open.back().prev;
      open.push_back({!sameMap(m, n), compose(outerNow, m), compose(outerPrev, n)});
      openChanged += open.back().changed;
    } else if (op.code == OpCode::EndMap && !open.empty()) {
      openChanged -= open.back().changed;
      open.pop_back();
    } else if (op.code == OpCode::Prims) {
      ctx.mapChanged = openChanged > 0;
      ctx.now = open.empty() ? Placement{} : open.back().now;
      ctx.prev = open.empty() ? Placement{} : open.back().prev;
      for (uint32_t k = 0; k < op.count; ++k) fn(op, op.primBegin + k, op.first + k, ctx);
    }
  }
}

// Steepest slope of x -> (1 - x^2)^k on [0, 1] (at x = 1 / sqrt(2k - 1)); infinite for k < 1.
float kernelSlope(float k) {
  if (!(k >= 1.0f)) return kUnbounded;
  double x = 1.0 / std::sqrt(2.0 * double(k) - 1.0);
  return float(2.0 * double(k) * x * std::pow(1.0 - x * x, double(k) - 1.0));
}

float moved(const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b); }

// How far a unit direction turns when vector v0 becomes v1: |v1/|v1| - v0/|v0|| <= 2 |v1 - v0| / min |v|.
float turned(const glm::vec3& v0, const glm::vec3& v1) {
  float l = std::min(glm::length(v0), glm::length(v1));
  return l > 0.0f ? std::min(2.0f, 2.0f * moved(v0, v1) / l) : 2.0f;
}

// A skeletal primitive placed in world space (through similarity maps: distances scale).
struct Placed {
  Skeleton skeleton;
  std::vector<glm::vec3> curve;
  float radius = 0.0f;
};

Placed place(const FieldProgram& program, const SkeletalPrimitive& p, const Placement& at) {
  Placed r;
  r.skeleton = p.skeleton;
  Skeleton& s = r.skeleton;
  auto point = [&](const glm::vec3& c) { return at.origin + at.linear * c; };
  s.p0 = point(s.p0);
  s.p2 = point(s.p2);
  const bool normal = s.kind == SkeletonKind::Disc || s.kind == SkeletonKind::Circle;
  s.p1 = normal ? at.linear * s.p1 / at.scale : point(s.p1);
  s.r0 *= at.scale;
  s.r1 *= at.scale;
  if (s.kind == SkeletonKind::Curve)
    for (int k = 0; k < s.curveCount; ++k) r.curve.push_back(point(program.curvePoints[p.curveFirst + uint32_t(k)]));
  r.radius = p.radius * at.scale;
  return r;
}

// Bound on how far any point of the skeleton moved (the Hausdorff distance between the two
// skeletons, so the distance from any x to it changes at most by this much).
float skeletonMove(const Placed& a, const Placed& b) {
  const Skeleton &s = a.skeleton, &t = b.skeleton;
  const float d0 = moved(s.p0, t.p0), d1 = moved(s.p1, t.p1);
  const float dr = std::max(std::abs(s.r0 - t.r0), std::abs(s.r1 - t.r1));
  const float rMax = std::max({s.r0, s.r1, t.r0, t.r1});
  switch (s.kind) {
    case SkeletonKind::Point: return d0;
    case SkeletonKind::Sphere: return d0 + std::abs(s.r0 - t.r0);
    case SkeletonKind::Segment: return std::max(d0, d1);
    case SkeletonKind::Triangle: return std::max({d0, d1, moved(s.p2, t.p2)});
    case SkeletonKind::Cylinder:
    case SkeletonKind::Cone:
      // Axis points move by at most max(d0, d1); a rim point also turns with the axis.
      return std::max(d0, d1) + dr + rMax * turned(s.p1 - s.p0, t.p1 - t.p0);
    case SkeletonKind::Disc:
    case SkeletonKind::Circle:  // p1 is the unit normal
      return d0 + dr + rMax * moved(s.p1, t.p1);
    case SkeletonKind::Curve: {
      float m = 0.0f;
      for (size_t k = 0; k < a.curve.size() && k < b.curve.size(); ++k) m = std::max(m, moved(a.curve[k], b.curve[k]));
      return 2.0f * m;  // Catmull-Rom weights (with reflected ends) sum to at most 1.75 in magnitude
    }
  }
  return kUnbounded;
}

float skeletalChange(const FieldProgram& now, const FieldProgram& prev, uint32_t i, const Context& ctx) {
  const SkeletalPrimitive &p = now.skeletal[i], &q = prev.skeletal[i];
  if (p.skeleton.kind != q.skeleton.kind || p.skeleton.curveCount != q.skeleton.curveCount ||
      p.stiffness != q.stiffness)
    return kUnbounded;
  // Under changed maps the primitive is compared in world space (similarity maps only); under
  // unchanged ones in its own space (the same map applies to both frames' fields).
  if (ctx.mapChanged && !(ctx.now.similar && ctx.prev.similar)) return kUnbounded;
  const Placed a = place(now, p, ctx.mapChanged ? ctx.now : Placement{});
  const Placed b = place(prev, q, ctx.mapChanged ? ctx.prev : Placement{});
  const float rMin = std::min(a.radius, b.radius);
  if (!(rMin > 0.0f)) return kUnbounded;
  const float slope = kernelSlope(p.stiffness);
  const float iMax = std::max(std::abs(p.intensity), std::abs(q.intensity));
  const float shape = skeletonMove(a, b) + std::abs(a.radius - b.radius);
  if (shape == 0.0f) return std::abs(p.intensity - q.intensity);
  return std::abs(p.intensity - q.intensity) + iMax * slope * shape / rMin;
}

// Lipschitz constant of an operator in the sum of its operands' changes.
float operatorFactor(OpCode code) {
  switch (code) {
    case OpCode::Sum:
    case OpCode::Max:
    case OpCode::Min:
    case OpCode::HyperBlend:
    case OpCode::Difference:
    case OpCode::BeginMap:
    case OpCode::EndMap:
    case OpCode::Prims:
    case OpCode::Const: return 1.0f;
    case OpCode::RUnion:
    case OpCode::RIntersection: return 2.0f;  // d/ds (s1 + s2 +- sqrt(s1^2 + s2^2)) lies in [0, 2]
    case OpCode::BoundedBlend:
    case OpCode::Remap: return kUnbounded;
  }
  return kUnbounded;
}

}  // namespace

bool sameStructure(const FieldProgram& a, const FieldProgram& b) {
  if (a.threshold != b.threshold || a.ops.size() != b.ops.size() || a.params != b.params ||
      a.maps.size() != b.maps.size() || a.primitiveCount() != b.primitiveCount() ||
      a.skeletal.size() != b.skeletal.size() || a.convolution.size() != b.convolution.size() ||
      a.capsules.size() != b.capsules.size() || a.curvePoints.size() != b.curvePoints.size())
    return false;
  for (size_t i = 0; i < a.ops.size(); ++i) {
    const FieldOp &x = a.ops[i], &y = b.ops[i];
    if (x.code != y.code || x.primClass != y.primClass || x.combineMax != y.combineMax || x.first != y.first ||
        x.count != y.count || x.primBegin != y.primBegin || x.param != y.param || x.emptyValue != y.emptyValue)
      return false;
  }
  return true;
}

std::vector<uint8_t> changedPrimitives(const FieldProgram& now, const FieldProgram& prev) {
  std::vector<uint8_t> changed(now.primitiveCount(), 1);
  forEachPrimitive(now, prev, [&](const FieldOp& op, uint32_t g, uint32_t local, const Context& ctx) {
    const PrimitiveBound &x = now.primitiveBounds[g], &y = prev.primitiveBounds[g];
    bool sameBound = x.a == y.a && x.b == y.b && x.radius == y.radius && x.box.min == y.box.min && x.box.max == y.box.max;
    changed[g] = ctx.mapChanged || !sameBound || !samePrimitive(now, prev, op.primClass, local);
  });
  return changed;
}

std::vector<float> primitiveChangeBounds(const FieldProgram& now, const FieldProgram& prev) {
  std::vector<float> bound(now.primitiveCount(), kUnbounded);
  std::vector<uint32_t> opOf(now.primitiveCount(), 0);  // the Prims op of each primitive
  std::vector<float> opFactor(now.ops.size(), 1.0f);
  for (size_t i = 0; i < now.ops.size(); ++i) {
    const float f = operatorFactor(now.ops[i].code);
    if (f == 1.0f) continue;
    for (uint32_t j = now.ops[i].subtreeBegin; j < i; ++j) opFactor[j] *= f;
  }
  for (size_t i = 0; i < now.ops.size(); ++i)
    if (now.ops[i].code == OpCode::Prims)
      for (uint32_t k = 0; k < now.ops[i].count; ++k) opOf[now.ops[i].primBegin + k] = uint32_t(i);
  forEachPrimitive(now, prev, [&](const FieldOp& op, uint32_t g, uint32_t local, const Context& ctx) {
    if (!ctx.mapChanged && samePrimitive(now, prev, op.primClass, local)) {
      bound[g] = 0.0f;
      return;
    }
    if (op.primClass != PrimClass::Skeletal) return;  // unbounded
    const float own = skeletalChange(now, prev, local, ctx);
    bound[g] = own == 0.0f ? 0.0f : own * opFactor[opOf[g]];
  });
  return bound;
}

}  // namespace animorph
