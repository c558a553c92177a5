#include "field/field_program.h"

#include <algorithm>
#include <functional>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>

#include "field/convolution_segment.h"
#include "field/potential.h"

namespace animorph {

namespace {

constexpr int kChunk = 1024;

float distToSegment(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b) {
  return glm::length(x - closestOnSegment(x, a, b));
}

bool uniformScaleRigid(const glm::mat3& m, float& scale) {
  float s0 = glm::length(m[0]), s1 = glm::length(m[1]), s2 = glm::length(m[2]);
  scale = s0;
  float tol = 1e-4f * s0;
  return std::abs(s0 - s1) <= tol && std::abs(s0 - s2) <= tol && std::abs(glm::dot(m[0], m[1])) <= tol * s0 &&
         std::abs(glm::dot(m[0], m[2])) <= tol * s0 && std::abs(glm::dot(m[1], m[2])) <= tol * s0;
}

Bounds intersect(const Bounds& a, const Bounds& b) {
  Bounds r;
  if (a.empty() || b.empty()) return r;
  r.min = glm::max(a.min, b.min);
  r.max = glm::min(a.max, b.max);
  if (r.min.x > r.max.x || r.min.y > r.max.y || r.min.z > r.max.z) return Bounds{};
  return r;
}

Bounds infiniteBounds() {
  Bounds b;
  b.min = glm::vec3(-INFINITY);
  b.max = glm::vec3(INFINITY);
  return b;
}

// The closed boxes share a point (false when either is empty).
bool boxesOverlap(const Bounds& a, const Bounds& box) {
  return !(a.min.x > box.max.x || a.max.x < box.min.x || a.min.y > box.max.y || a.max.y < box.min.y ||
           a.min.z > box.max.z || a.max.z < box.min.z);
}

bool isInfinite(const Bounds& b) { return !b.empty() && (std::isinf(b.min.x) || std::isinf(b.max.x)); }

float applyScalar(OpCode code, const float* v, uint32_t n, const float* prm, float T) {
  switch (code) {
    case OpCode::Sum: {
      float s = 0.0f;
      for (uint32_t i = 0; i < n; ++i) s += v[i];
      return s;
    }
    case OpCode::Max: {
      float s = v[0];
      for (uint32_t i = 1; i < n; ++i) s = std::max(s, v[i]);
      return s;
    }
    case OpCode::Min: {
      float s = v[0];
      for (uint32_t i = 1; i < n; ++i) s = std::min(s, v[i]);
      return s;
    }
    case OpCode::HyperBlend: {
      float d[64];
      float tmp[64];
      uint32_t m = std::min<uint32_t>(n, 64);
      for (uint32_t i = 0; i < m; ++i) tmp[i] = v[i];
      return hyperBlend(tmp, int(m), prm[0], d);
    }
    case OpCode::Difference: return std::min(v[0], 2.0f * T - v[1]);
    case OpCode::RUnion: {
      float d1, d2;
      return T + rUnion(v[0] - T, v[1] - T, d1, d2);
    }
    case OpCode::RIntersection: {
      float d1, d2;
      return T + rIntersection(v[0] - T, v[1] - T, d1, d2);
    }
    case OpCode::BoundedBlend: {
      float d[3];
      BoundedBlendParams bp{prm[0], prm[1], prm[2], prm[3]};
      return T + boundedBlend(v[0] - T, v[1] - T, v[2] - T, bp, d);
    }
    case OpCode::Remap: {
      float d;
      return remapPotential(v[0], prm[0], prm[1], T, d);
    }
    default: return 0.0f;
  }
}


// Operators that fold left: op(v0..vn) = op(op(v0..vk), vk+1..vn). Sum, Max and Min
// exactly (the same left-to-right order); HyperBlend up to rounding, as (sum p^q)^(1/q)
// of nonnegative operands nests.
bool foldsLeft(OpCode c) {
  return c == OpCode::Sum || c == OpCode::Max || c == OpCode::Min || c == OpCode::HyperBlend;
}

// Rewrites every folding operator with more than kFoldOperands operands as a chain of
// operators of at most kFoldOperands, each taking the previous one's value first, placed
// right after the operand that completes its chunk. The operands' own ops are untouched
// (Prims ops keep their primitives), so a blend of 20 children holds at most 3 pending values
// on the stack instead of 20: the GPU's operand stack is bounded (AM_POLY_MAX_STACK), and
// the CPU's chunked stack no longer grows with an operator's width.
void foldWideOperators(std::vector<FieldOp>& ops) {
  constexpr uint32_t K = kFoldOperands;
  bool any = false;
  for (const FieldOp& op : ops) any |= foldsLeft(op.code) && op.count > K;
  if (!any) return;
  // Which op completes each operand: a push, or the EndMap closing a map around it.
  std::vector<uint32_t> doneAt;
  std::vector<int32_t> insertFrom(ops.size(), -1);  // insert a copy of ops[from] after this op
  std::vector<uint32_t> finalCount(ops.size(), 0);
  for (uint32_t i = 0; i < ops.size(); ++i) {
    const FieldOp& op = ops[i];
    switch (op.code) {
      case OpCode::Prims:
      case OpCode::Const: doneAt.push_back(i); break;
      case OpCode::BeginMap: break;
      case OpCode::EndMap:
        if (!doneAt.empty()) doneAt.back() = i;
        break;
      default: {
        uint32_t n = std::min<uint32_t>(op.count, uint32_t(doneAt.size()));
        size_t base = doneAt.size() - n;
        if (foldsLeft(op.code) && n > K) {
          // Chunks: operands 0..K-1, then the running value and K-1 more, ...
          uint32_t next = K;
          insertFrom[doneAt[base + K - 1]] = int32_t(i);
          while (n - next > K - 1) {
            insertFrom[doneAt[base + next + K - 2]] = int32_t(i);
            next += K - 1;
          }
          finalCount[i] = 1 + (n - next);
        }
        doneAt.resize(base);
        doneAt.push_back(i);
      }
    }
  }
  std::vector<FieldOp> out;
  out.reserve(ops.size() + ops.size() / (K - 1) + 1);
  for (uint32_t i = 0; i < ops.size(); ++i) {
    FieldOp op = ops[i];
    if (finalCount[i]) op.count = finalCount[i];
    out.push_back(op);
    if (insertFrom[i] >= 0) {
      FieldOp part = ops[size_t(insertFrom[i])];
      part.count = K;
      out.push_back(part);
    }
  }
  ops = std::move(out);
}
}  // namespace

// ------------------------------------------------------------------ building

PrimitiveBound FieldProgram::worldBound(const glm::vec3& a, const glm::vec3& b, float radius) const {
  PrimitiveBound pb;
  pb.a = a;
  pb.b = b;
  pb.radius = radius;
  pb.box.add(glm::min(a, b) - glm::vec3(radius));
  pb.box.add(glm::max(a, b) + glm::vec3(radius));
  for (auto it = openMaps_.rbegin(); it != openMaps_.rend(); ++it) {
    const SpaceMap& m = maps[*it];
    Bounds box = m.worldBounds(pb.box);
    float s;
    if (m.kind == SpaceMapKind::Affine && uniformScaleRigid(m.forwardLinear, s)) {
      pb.a = m.toWorld(pb.a);
      pb.b = m.toWorld(pb.b);
      pb.radius *= s;
      Bounds capBox;
      capBox.add(glm::min(pb.a, pb.b) - glm::vec3(pb.radius));
      capBox.add(glm::max(pb.a, pb.b) + glm::vec3(pb.radius));
      pb.box = intersect(box, capBox);
      if (pb.box.empty()) pb.box = capBox;
    } else {
      pb.box = box;
      pb.a = pb.b = box.center();
      pb.radius = 0.5f * box.diagonal();
    }
  }
  return pb;
}

bool FieldProgram::pushPrims(PrimClass cls, uint32_t local, bool combineWithPrevious, bool combineMax,
                             const PrimitiveBound& b) {
  uint32_t global = uint32_t(primitiveBounds.size());
  primitiveBounds.push_back(b);
  if (combineWithPrevious && !ops.empty()) {
    FieldOp& last = ops.back();
    if (last.code == OpCode::Prims && last.primClass == cls && last.combineMax == combineMax &&
        last.first + last.count == local && last.primBegin + last.count == global) {
      ++last.count;
      return false;
    }
  }
  FieldOp op;
  op.code = OpCode::Prims;
  op.primClass = cls;
  op.combineMax = combineMax;
  op.first = local;
  op.count = 1;
  op.primBegin = global;
  ops.push_back(op);
  return true;
}

bool FieldProgram::addSkeletal(const SkeletalPrimitive& p, bool combineWithPrevious, bool combineMax) {
  glm::vec3 a, b;
  float r;
  Skeleton s = p.skeleton;
  s.curve = p.skeleton.kind == SkeletonKind::Curve ? curvePoints.data() + p.curveFirst : nullptr;
  skeletonEnclosingCapsule(s, a, b, r);
  uint32_t local = uint32_t(skeletal.size());
  skeletal.push_back(p);
  skeletalReach.push_back({a, b, r + std::max(p.radius, 0.0f)});
  return pushPrims(PrimClass::Skeletal, local, combineWithPrevious, combineMax,
                   worldBound(a, b, r + std::max(p.radius, 0.0f)));
}

bool FieldProgram::addConvolution(const glm::vec3& a, const glm::vec3& b, float radius, float sharpness, float eps,
                                  bool combineWithPrevious) {
  glm::vec3 ab = b - a;
  float len = glm::length(ab);
  glm::vec3 dir = len > 1e-12f ? ab / len : glm::vec3(1, 0, 0);
  double w = convolutionWeightForRadius(radius, sharpness, threshold);
  double cut = convolutionCutoffRadius(len, sharpness, w, threshold, eps);
  ConvolutionData& c = convolution;
  uint32_t local = uint32_t(c.size());
  c.bx.push_back(a.x);
  c.by.push_back(a.y);
  c.bz.push_back(a.z);
  c.ax.push_back(dir.x);
  c.ay.push_back(dir.y);
  c.az.push_back(dir.z);
  c.length.push_back(len);
  c.weight.push_back(float(w));
  c.sharpness.push_back(sharpness);
  c.cut2.push_back(float(cut * cut));
  return pushPrims(PrimClass::Convolution, local, combineWithPrevious, false, worldBound(a, b, float(cut)));
}

bool FieldProgram::addCapsule(const CapsulePrimitive& cp, bool combineWithPrevious, bool combineMax) {
  uint32_t local = uint32_t(capsules.size());
  capsules.push_back(cp);
  return pushPrims(PrimClass::Capsule, local, combineWithPrevious, combineMax,
                   worldBound(cp.a, cp.b, 2.0f * std::max(cp.radius, 0.0f)));
}

void FieldProgram::addConstant(float potential) {
  FieldOp op;
  op.code = OpCode::Const;
  op.emptyValue = potential;
  ops.push_back(op);
}

void FieldProgram::addOperator(OpCode code, uint32_t operands, const float* opParams, int paramCount) {
  FieldOp op;
  op.code = code;
  op.count = operands;
  op.param = uint32_t(params.size());
  for (int i = 0; i < paramCount; ++i) params.push_back(opParams[i]);
  ops.push_back(op);
}

void FieldProgram::beginMap(const SpaceMap& m) {
  FieldOp op;
  op.code = OpCode::BeginMap;
  op.first = uint32_t(maps.size());
  openMaps_.push_back(op.first);
  openBegins_.push_back(uint32_t(ops.size()));
  maps.push_back(m);
  ops.push_back(op);
}

void FieldProgram::endMap() {
  assert(!openMaps_.empty());
  FieldOp op;
  op.code = OpCode::EndMap;
  op.first = openMaps_.back();
  openMaps_.pop_back();
  openBegins_.pop_back();
  ops.push_back(op);
}

void FieldProgram::finish() {
  static std::atomic<uint64_t> nextIdentity{1};
  identity_ = nextIdentity.fetch_add(1);
  foldWideOperators(ops);
  // Empty values, subtree extents and stack depth by a symbolic run.
  std::vector<float> vals;
  std::vector<uint32_t> begins;
  std::vector<uint32_t> mapBegins;
  std::vector<Bounds> boxes;
  std::vector<Bounds> reach;  // supports under each open map
  mapReach_.assign(maps.size(), Bounds{});
  int depth = 0;
  maxStack_ = 0;
  maxMapDepth_ = 0;
  const float T = threshold;
  for (uint32_t i = 0; i < ops.size(); ++i) {
    FieldOp& op = ops[i];
    switch (op.code) {
      case OpCode::Prims: {
        op.emptyValue = 0.0f;
        Bounds b;
        for (uint32_t k = 0; k < op.count; ++k) b.add(primitiveBounds[op.primBegin + k].box);
        vals.push_back(0.0f);
        begins.push_back(i);
        boxes.push_back(b);
        if (!reach.empty()) reach.back().add(b);
        op.subtreeBegin = i;
        break;
      }
      case OpCode::Const:
        vals.push_back(op.emptyValue);
        begins.push_back(i);
        boxes.push_back(op.emptyValue >= T ? infiniteBounds() : Bounds{});
        op.subtreeBegin = i;
        break;
      case OpCode::BeginMap:
        mapBegins.push_back(i);
        reach.emplace_back();
        op.subtreeBegin = i;
        ++depth;
        maxMapDepth_ = std::max(maxMapDepth_, depth);
        break;
      case OpCode::EndMap: {
        op.subtreeBegin = mapBegins.back();
        mapBegins.pop_back();
        mapReach_[op.first] = reach.back();
        reach.pop_back();
        if (!reach.empty()) reach.back().add(mapReach_[op.first]);
        --depth;
        begins.back() = op.subtreeBegin;
        op.emptyValue = vals.back();
        boxes.back() = maps[op.first].worldBounds(boxes.back());
        break;
      }
      default: {
        uint32_t n = op.count;
        assert(vals.size() >= n && n > 0);
        size_t base = vals.size() - n;
        float v = applyScalar(op.code, vals.data() + base, n, params.data() + op.param, T);
        uint32_t b0 = begins[base];
        Bounds box;
        switch (op.code) {
          case OpCode::Min:
          case OpCode::RIntersection:
            box = boxes[base];
            for (uint32_t k = 1; k < n; ++k) {
              const Bounds& o = boxes[base + k];
              if (isInfinite(box)) box = o;
              else if (!isInfinite(o)) box = intersect(box, o);
            }
            break;
          case OpCode::Difference: box = boxes[base]; break;
          default:
            for (uint32_t k = 0; k < n; ++k) {
              if (isInfinite(boxes[base + k])) box = infiniteBounds();
              if (!isInfinite(box)) box.add(boxes[base + k]);
            }
        }
        if (v >= T) box = infiniteBounds();
        vals.resize(base + 1);
        begins.resize(base + 1);
        boxes.resize(base + 1);
        vals[base] = v;
        begins[base] = b0;
        boxes[base] = box;
        op.subtreeBegin = b0;
        op.emptyValue = v;
      }
    }
    maxStack_ = std::max(maxStack_, int(vals.size()));
  }
  outermostEnd_.assign(ops.size(), 0);
  for (uint32_t i = 0; i < ops.size(); ++i) outermostEnd_[i] = i;
  for (uint32_t j = 0; j < ops.size(); ++j) {
    uint32_t b = ops[j].subtreeBegin;
    outermostEnd_[b] = std::max(outermostEnd_[b], j);
  }
  primsBefore_.assign(ops.size() + 1, 0);
  for (uint32_t i = 0; i < ops.size(); ++i)
    primsBefore_[i + 1] = primsBefore_[i] + (ops[i].code == OpCode::Prims ? ops[i].count : 0);
  if (vals.size() != 1) {
    // Empty or malformed program: evaluates to "outside" everywhere.
    ops.clear();
    addConstant(0.0f);
    outermostEnd_.assign(1, 0);
    primsBefore_.assign(2, 0);
    maxStack_ = 1;
    bounds_ = Bounds{};
    unbounded_ = false;
    return;
  }
  unbounded_ = isInfinite(boxes[0]);
  bounds_ = unbounded_ ? Bounds{} : boxes[0];
}

// ------------------------------------------------------------------ specialising

void FieldProgram::specialiseAll(ActiveProgram& out) const {
  out.ops = ops;
  out.indices.clear();
  for (FieldOp& op : out.ops)
    if (op.code == OpCode::Prims) {
      uint32_t off = uint32_t(out.indices.size());
      for (uint32_t k = 0; k < op.count; ++k) out.indices.push_back(op.first + k);
      op.first = off;
    }
  out.primitiveCount = primitiveBounds.size();
}

void FieldProgram::specialise(const std::vector<uint32_t>& active, ActiveProgram& out) const {
  out.ops.clear();
  out.indices.clear();
  out.primitiveCount = active.size();
  // One forward walk that jumps over every subtree holding no active primitive: its cost is the
  // ops it emits plus the active primitives, not the size of the whole program. The primitives
  // of ops i..e are the global ids [primsBefore_[i], primsBefore_[e + 1]).
  //
  // Operands that are exactly zero (a constant 0, primitives none of which is active) are dropped
  // from sums as they are emitted: a + 0 is a, and the other operands keep their order, so the
  // values are the same and the evaluation runs fewer ops.
  struct Operand {
    uint32_t start;  // first op of the operand in out.ops
    bool zero;       // a single op pushing exactly 0
  };
  thread_local std::vector<Operand> operands;
  thread_local std::vector<uint32_t> mapStarts;
  operands.clear();
  mapStarts.clear();
  auto emitted = [&](const FieldOp& op) {
    const uint32_t at = uint32_t(out.ops.size()) - 1;
    switch (op.code) {
      case OpCode::Const: operands.push_back({at, op.emptyValue == 0.0f}); return;
      case OpCode::Prims: operands.push_back({at, op.count == 0}); return;
      case OpCode::BeginMap: mapStarts.push_back(at); return;
      case OpCode::EndMap:  // the map's subtree is one operand, from its BeginMap
        operands.back() = {mapStarts.back(), false};
        mapStarts.pop_back();
        return;
      default: break;
    }
    const size_t n = op.count, base = operands.size() - n;
    const uint32_t first = operands[base].start;
    if (op.code == OpCode::Sum) {
      size_t zeros = 0;
      for (size_t k = base; k < operands.size(); ++k) zeros += operands[k].zero;
      if (zeros > 0) {
        out.ops.pop_back();  // the Sum, emitted again below if still needed
        // Operands before the first zero stay where they are (the first is often a long chain).
        size_t k = base, kept = 0;
        for (; !operands[k].zero; ++k) ++kept;
        uint32_t w = operands[k].start;
        for (; k < operands.size(); ++k) {
          uint32_t end = k + 1 < operands.size() ? operands[k + 1].start : uint32_t(out.ops.size());
          if (operands[k].zero) continue;
          for (uint32_t j = operands[k].start; j < end; ++j) out.ops[w + (j - operands[k].start)] = out.ops[j];
          w += end - operands[k].start;
          ++kept;
        }
        out.ops.resize(w);
        operands.resize(base);
        if (kept == 0) {
          FieldOp c;
          c.code = OpCode::Const;
          c.emptyValue = 0.0f;
          out.ops.push_back(c);
          operands.push_back({first, true});
        } else {
          if (kept > 1) {
            FieldOp sum = op;
            sum.count = uint32_t(kept);
            out.ops.push_back(sum);
          }
          operands.push_back({first, false});
        }
        return;
      }
    }
    operands.resize(base);
    operands.push_back({first, false});
  };
  size_t cursor = 0;
  for (size_t i = 0; i < ops.size();) {
    uint32_t e = outermostEnd_[i];
    // Only leaves and map openings start subtrees; operators close them.
    bool startsSubtree = ops[i].code == OpCode::Prims || ops[i].code == OpCode::BeginMap;
    if (startsSubtree) {
      while (cursor < active.size() && active[cursor] < primsBefore_[i]) ++cursor;
    }
    if (startsSubtree && !(cursor < active.size() && active[cursor] < primsBefore_[e + 1])) {
      FieldOp c;
      c.code = OpCode::Const;
      c.emptyValue = ops[e].emptyValue;
      out.ops.push_back(c);
      emitted(c);
      i = e + 1;
      continue;
    }
    FieldOp op = ops[i];
    if (op.code == OpCode::Prims) {
      while (cursor < active.size() && active[cursor] < op.primBegin) ++cursor;
      uint32_t off = uint32_t(out.indices.size());
      while (cursor < active.size() && active[cursor] < op.primBegin + op.count) {
        out.indices.push_back(op.first + (active[cursor] - op.primBegin));
        ++cursor;
      }
      op.first = off;
      op.count = uint32_t(out.indices.size()) - off;
    }
    out.ops.push_back(op);
    emitted(op);
    ++i;
  }
}

void FieldProgram::primitivesReaching(const Bounds& box, std::vector<uint32_t>& out,
                                      const std::vector<uint32_t>* candidates) const {
  out.clear();
  glm::vec3 c = box.center();
  float half = 0.5f * box.diagonal();
  auto test = [&](uint32_t g) {
    const PrimitiveBound& b = primitiveBounds[g];
    if (!boxesOverlap(b.box, box)) return;
    if (distToSegment(c, b.a, b.b) > b.radius + half) return;
    out.push_back(g);
  };
  if (candidates) {
    for (uint32_t g : *candidates) test(g);
  } else {
    for (uint32_t g = 0; g < primitiveBounds.size(); ++g) test(g);
  }
}

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
      case OpCode::Prims: {
        Interval acc{0.0f, 0.0f};
        if (op.primClass == PrimClass::Convolution) {
          thread_local std::vector<float> los, his;
          los.resize(op.count);
          his.resize(op.count);
          convolutionIntervalKernel(convolution, prog.indices.data() + op.first, int(op.count), c, rho, los.data(),
                                    his.data());
          for (uint32_t k = 0; k < op.count; ++k) {
            acc.lo += los[k];
            acc.hi += his[k];
          }
          st.push_back(acc);
          break;
        }
        for (uint32_t k = 0; k < op.count; ++k) {
          uint32_t i = prog.indices[op.first + k];
          Interval v{0.0f, 0.0f};
          if (op.primClass == PrimClass::Skeletal) {
            const SkeletalPrimitive& p = skeletal[i];
            Skeleton s = p.skeleton;
            if (s.kind == SkeletonKind::Curve) s.curve = curvePoints.data() + p.curveFirst;
            float d = glm::length(c - closestOnSkeleton(s, c));
            float g0 = potentialAt(std::max(0.0f, d - rho), p.radius, p.intensity, p.stiffness);
            float g1 = potentialAt(d + rho, p.radius, p.intensity, p.stiffness);
            v = {std::min(g0, g1), std::max(g0, g1)};
          } else {
            const CapsulePrimitive& cp = capsules[i];
            float d = distToSegment(c, cp.a, cp.b);
            auto pot = [&](float dd) { return cp.radius > 0.0f ? T * std::max(0.0f, 2.0f - dd / cp.radius) : 0.0f; };
            v = {pot(d + rho), pot(std::max(0.0f, d - rho))};
          }
          if (op.combineMax) acc = {std::max(acc.lo, v.lo), std::max(acc.hi, v.hi)};
          else acc = {acc.lo + v.lo, acc.hi + v.hi};
        }
        st.push_back(acc);
        break;
      }
      case OpCode::Const: st.push_back({op.emptyValue, op.emptyValue}); break;
      case OpCode::BeginMap: {
        balls.push_back(glm::vec4(c, rho));
        const SpaceMap& m = maps[op.first];
        float stretch = m.localStretchBound(c, rho);
        c = m.toLocal(c);
        rho = std::isinf(stretch) ? INFINITY : rho * stretch * 1.0001f;
        break;
      }
      case OpCode::EndMap: {
        c = glm::vec3(balls.back());
        rho = balls.back().w;
        balls.pop_back();
        break;
      }
      default: {
        uint32_t n = op.count;
        size_t base = st.size() - n;
        const float* prm = params.data() + op.param;
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
        st.resize(base + 1);
        st[base] = r;
      }
    }
  }
  if (st.empty()) return {-T, -T};
  return {st.back().lo - T, st.back().hi - T};
}

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

void FieldEvaluator::runChunk(const FieldProgram& P, const ActiveProgram& A, const float* x, const float* y,
                              const float* z, int n, float* fOut, float* gxOut, float* gyOut, float* gzOut) {
  const bool grad = gxOut != nullptr;
  const float T = P.threshold;
  int sp = 0;  // stack size
  int level = 0;
  levels_.resize(size_t(P.maxMapDepth() + 1) * 3);
  const float** cx = levels_.data();
  const float** cy = cx + P.maxMapDepth() + 1;
  const float** cz = cy + P.maxMapDepth() + 1;
  cx[0] = x;
  cy[0] = y;
  cz[0] = z;
  // Box of the points at each map level (skeletal primitives are skipped against it).
  levelBoxes_.resize(size_t(P.maxMapDepth() + 1) * 2);
  glm::vec3* boxes = levelBoxes_.data();
  auto pointsBox = [&](const float* bx, const float* by, const float* bz, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(INFINITY);
    hi = glm::vec3(-INFINITY);
    for (int i = 0; i < n; ++i) {
      lo = glm::min(lo, glm::vec3(bx[i], by[i], bz[i]));
      hi = glm::max(hi, glm::vec3(bx[i], by[i], bz[i]));
    }
  };
  pointsBox(x, y, z, boxes[0], boxes[1]);
  auto F = [&](int s) { return stack_.data() + size_t(s) * 4 * kChunk; };
  auto GX = [&](int s) { return F(s) + kChunk; };
  auto GY = [&](int s) { return F(s) + 2 * kChunk; };
  auto GZ = [&](int s) { return F(s) + 3 * kChunk; };
  auto pushConstant = [&](float value) {
    std::fill(F(sp), F(sp) + n, value);
    if (grad) {
      std::fill(GX(sp), GX(sp) + n, 0.0f);
      std::fill(GY(sp), GY(sp) + n, 0.0f);
      std::fill(GZ(sp), GZ(sp) + n, 0.0f);
    }
    ++sp;
  };
  const glm::vec3 worldLo = boxes[0], worldHi = boxes[1];
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
      case OpCode::Prims: {
        float* f = F(sp);
        std::fill(f, f + n, 0.0f);
        if (grad) {
          std::fill(GX(sp), GX(sp) + n, 0.0f);
          std::fill(GY(sp), GY(sp) + n, 0.0f);
          std::fill(GZ(sp), GZ(sp) + n, 0.0f);
        }
        const uint32_t* idx = A.indices.data() + op.first;
        float* gx = grad ? GX(sp) : nullptr;
        float* gy = grad ? GY(sp) : nullptr;
        float* gz = grad ? GZ(sp) : nullptr;
        switch (op.primClass) {
          case PrimClass::Convolution:
            convolutionKernel(P.convolution, idx, int(op.count), cx[level], cy[level], cz[level], n, f, gx, gy, gz);
            break;
          case PrimClass::Skeletal:
            skeletalKernel(P, idx, int(op.count), op.combineMax, cx[level], cy[level], cz[level], n,
                           boxes[2 * level], boxes[2 * level + 1], f, gx, gy, gz);
            break;
          case PrimClass::Capsule:
            capsuleKernel(P.capsules, T, idx, int(op.count), op.combineMax, cx[level], cy[level], cz[level], n, f,
                          gx, gy, gz);
            break;
        }
        ++sp;
        break;
      }
      case OpCode::Const: pushConstant(op.emptyValue); break;
      case OpCode::BeginMap: {
        const SpaceMap& m = P.maps[op.first];
        float* out = coords_.data() + size_t(level + 1) * 3 * kChunk;
        float* __restrict ox = out;  // the levels' coordinates never overlap: the loops vectorise
        float* __restrict oy = out + kChunk;
        float* __restrict oz = out + 2 * kChunk;
        const float* __restrict ix = cx[level];
        const float* __restrict iy = cy[level];
        const float* __restrict iz = cz[level];
        if (m.kind == SpaceMapKind::Affine) {
          const glm::mat3& L = m.linear;
          const glm::vec3 o = m.origin;
          for (int i = 0; i < n; ++i) {
            float dx = ix[i] - o.x, dy = iy[i] - o.y, dz = iz[i] - o.z;
            ox[i] = L[0][0] * dx + L[1][0] * dy + L[2][0] * dz;
            oy[i] = L[0][1] * dx + L[1][1] * dy + L[2][1] * dz;
            oz[i] = L[0][2] * dx + L[1][2] * dy + L[2][2] * dz;
          }
        } else {
          for (int i = 0; i < n; ++i) {
            glm::vec3 q = m.toLocal({ix[i], iy[i], iz[i]});
            ox[i] = q.x;
            oy[i] = q.y;
            oz[i] = q.z;
          }
        }
        ++level;
        cx[level] = ox;
        cy[level] = oy;
        cz[level] = oz;
        if (m.kind == SpaceMapKind::Affine) {
          // The image of the parent box's corners bounds the image of its points.
          const glm::vec3 lo = boxes[2 * level - 2], hi = boxes[2 * level - 1];
          glm::vec3 nlo(INFINITY), nhi(-INFINITY);
          for (int c = 0; c < 8; ++c) {
            glm::vec3 q((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
            glm::vec3 r = m.linear * (q - m.origin);
            nlo = glm::min(nlo, r);
            nhi = glm::max(nhi, r);
          }
          const glm::vec3 pad = 1e-5f * (nhi - nlo) + 1e-6f * glm::max(glm::abs(nlo), glm::abs(nhi));  // rounding
          boxes[2 * level] = nlo - pad;
          boxes[2 * level + 1] = nhi + pad;
        } else {
          pointsBox(ox, oy, oz, boxes[2 * level], boxes[2 * level + 1]);
        }
        break;
      }
      case OpCode::EndMap: {
        const SpaceMap& m = P.maps[op.first];
        --level;
        if (grad) {
          float* gx = GX(sp - 1);
          float* gy = GY(sp - 1);
          float* gz = GZ(sp - 1);
          if (m.kind == SpaceMapKind::Affine) {
            const glm::mat3& L = m.linear;  // J = L; grad_world = L^T grad_local
            for (int i = 0; i < n; ++i) {
              float a = gx[i], b = gy[i], c = gz[i];
              gx[i] = L[0][0] * a + L[0][1] * b + L[0][2] * c;
              gy[i] = L[1][0] * a + L[1][1] * b + L[1][2] * c;
              gz[i] = L[2][0] * a + L[2][1] * b + L[2][2] * c;
            }
          } else {
            for (int i = 0; i < n; ++i) {
              glm::mat3 J;
              m.toLocal({cx[level][i], cy[level][i], cz[level][i]}, &J);
              glm::vec3 g = glm::transpose(J) * glm::vec3(gx[i], gy[i], gz[i]);
              gx[i] = g.x;
              gy[i] = g.y;
              gz[i] = g.z;
            }
          }
        }
        break;
      }
      default: {
        int cnt = int(op.count);
        int base = sp - cnt;
        float* f0 = F(base);
        float* gx0 = GX(base);
        float* gy0 = GY(base);
        float* gz0 = GZ(base);
        const float* prm = P.params.data() + op.param;
        switch (op.code) {
          case OpCode::Sum:
            for (int k = 1; k < cnt; ++k) {
              const float* fk = F(base + k);
              for (int i = 0; i < n; ++i) f0[i] += fk[i];
              if (grad) {
                const float* ax = GX(base + k);
                const float* ay = GY(base + k);
                const float* az = GZ(base + k);
                for (int i = 0; i < n; ++i) {
                  gx0[i] += ax[i];
                  gy0[i] += ay[i];
                  gz0[i] += az[i];
                }
              }
            }
            break;
          case OpCode::Max:
          case OpCode::Min: {
            bool mx = op.code == OpCode::Max;
            for (int k = 1; k < cnt; ++k) {
              const float* fk = F(base + k);
              if (grad) {
                const float* ax = GX(base + k);
                const float* ay = GY(base + k);
                const float* az = GZ(base + k);
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
            break;
          }
          case OpCode::HyperBlend: {
            float q = prm[0];
            float vals[64], d[64];
            int m = std::min(cnt, 64);
            for (int i = 0; i < n; ++i) {
              for (int k = 0; k < m; ++k) vals[k] = F(base + k)[i];
              float h = hyperBlend(vals, m, q, d);
              if (grad) {
                float sx = 0, sy = 0, sz = 0;
                for (int k = 0; k < m; ++k) {
                  sx += d[k] * GX(base + k)[i];
                  sy += d[k] * GY(base + k)[i];
                  sz += d[k] * GZ(base + k)[i];
                }
                gx0[i] = sx;
                gy0[i] = sy;
                gz0[i] = sz;
              }
              f0[i] = h;
            }
            break;
          }
          case OpCode::Difference: {
            const float* f1 = F(base + 1);
            for (int i = 0; i < n; ++i) {
              float other = 2.0f * T - f1[i];
              if (other < f0[i]) {
                f0[i] = other;
                if (grad) {
                  gx0[i] = -GX(base + 1)[i];
                  gy0[i] = -GY(base + 1)[i];
                  gz0[i] = -GZ(base + 1)[i];
                }
              }
            }
            break;
          }
          case OpCode::RUnion:
          case OpCode::RIntersection: {
            bool uni = op.code == OpCode::RUnion;
            const float* f1 = F(base + 1);
            for (int i = 0; i < n; ++i) {
              float d1, d2;
              float r = uni ? rUnion(f0[i] - T, f1[i] - T, d1, d2) : rIntersection(f0[i] - T, f1[i] - T, d1, d2);
              f0[i] = T + r;
              if (grad) {
                gx0[i] = d1 * gx0[i] + d2 * GX(base + 1)[i];
                gy0[i] = d1 * gy0[i] + d2 * GY(base + 1)[i];
                gz0[i] = d1 * gz0[i] + d2 * GZ(base + 1)[i];
              }
            }
            break;
          }
          case OpCode::BoundedBlend: {
            BoundedBlendParams bp{prm[0], prm[1], prm[2], prm[3]};
            const float* f1 = F(base + 1);
            const float* f2 = F(base + 2);
            for (int i = 0; i < n; ++i) {
              float d[3];
              float r = boundedBlend(f0[i] - T, f1[i] - T, f2[i] - T, bp, d);
              f0[i] = T + r;
              if (grad) {
                gx0[i] = d[0] * gx0[i] + d[1] * GX(base + 1)[i] + d[2] * GX(base + 2)[i];
                gy0[i] = d[0] * gy0[i] + d[1] * GY(base + 1)[i] + d[2] * GY(base + 2)[i];
                gz0[i] = d[0] * gz0[i] + d[1] * GZ(base + 1)[i] + d[2] * GZ(base + 2)[i];
              }
            }
            break;
          }
          case OpCode::Remap:
            for (int i = 0; i < n; ++i) {
              float d;
              f0[i] = remapPotential(f0[i], prm[0], prm[1], T, d);
              if (grad) {
                gx0[i] *= d;
                gy0[i] *= d;
                gz0[i] *= d;
              }
            }
            break;
          default: break;
        }
        sp = base + 1;
      }
    }
  }
  const float* f = F(0);
  for (int i = 0; i < n; ++i) fOut[i] = f[i] - T;
  if (grad) {
    std::copy(GX(0), GX(0) + n, gxOut);
    std::copy(GY(0), GY(0) + n, gyOut);
    std::copy(GZ(0), GZ(0) + n, gzOut);
  }
}

}  // namespace animorph
