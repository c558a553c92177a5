// FieldProgram, part 1 of 4: building a program from a BlobTree's flattened nodes (ops, primitive
// records, bounds). The other parts: field_program_specialise.cpp (a program cut down to a
// region), field_program_interval.cpp (interval bounds over a region), field_program_evaluate.cpp
// (batch evaluation of values and gradients).
#include "core/field/field_program.h"

#include <algorithm>
#include <functional>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/field/convolution_segment.h"
#include "core/field/potential.h"
#include "core/field/space_map_simd.h"

namespace animorph {
namespace {



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
  // Per-thread memory, kept: a program rebuilt every frame allocates nothing here once warm.
  thread_local std::vector<uint32_t> doneAt;
  thread_local std::vector<int32_t> insertFrom;  // insert a copy of ops[from] after this op
  thread_local std::vector<uint32_t> finalCount;
  doneAt.clear();
  insertFrom.assign(ops.size(), -1);
  finalCount.assign(ops.size(), 0);
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
  // The rewritten list goes to a per-thread buffer that is then swapped with ops: a program
  // rebuilt every frame (FieldProgram::reset) reuses both buffers instead of allocating.
  thread_local std::vector<FieldOp> out;
  out.clear();
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
  ops.swap(out);
}
}  // namespace

// ------------------------------------------------------------------ building

namespace {

// A new program identity (FieldProgram::identity, structureIdentity): unique in the process.
uint64_t nextProgramIdentity() {
  static std::atomic<uint64_t> next{1};
  return next.fetch_add(1);
}

uint64_t mixWord(uint64_t h, uint64_t w) {
  h = (h ^ w) * 0x9E3779B97F4A7C15ull;
  return h ^ (h >> 29);
}

// Digest of an unfolded op list (as the adds made it): every field the adds set, in order.
uint64_t digestOps(const std::vector<FieldOp>& ops) {
  uint64_t h = 0xCBF29CE484222325ull ^ ops.size();
  for (const FieldOp& op : ops) {
    uint32_t emptyBits;
    std::memcpy(&emptyBits, &op.emptyValue, sizeof emptyBits);
    h = mixWord(h, uint64_t(op.code) | uint64_t(op.primClass) << 8 | uint64_t(op.combineMax) << 16 |
                       uint64_t(op.count) << 32);
    h = mixWord(h, uint64_t(op.first) | uint64_t(op.primBegin) << 32);
    h = mixWord(h, uint64_t(op.param) | uint64_t(emptyBits) << 32);
  }
  return h;
}

// A primitive's capsule (a, b, radius) and box in its own space, where its world bound starts.
PrimitiveBound localBound(const glm::vec3& a, const glm::vec3& b, float radius) {
  PrimitiveBound pb;
  pb.a = a;
  pb.b = b;
  pb.radius = radius;
  pb.box.add(glm::min(a, b) - glm::vec3(radius));
  pb.box.add(glm::max(a, b) + glm::vec3(radius));
  return pb;
}

#if defined(__SSE2__)
// A primitive's bound in registers while it is carried up through the open maps.
struct LaneBound {
  __m128 a, b, boxMin, boxMax;
  float r;
  bool point;  // a and b the same bits: they stay so (one toWorld per level)
};

LaneBound laneBound(const PrimitiveBound& pb) {
  return {simd::load3(pb.a), simd::load3(pb.b), simd::load3(pb.box.min), simd::load3(pb.box.max), pb.radius,
          std::memcmp(&pb.a, &pb.b, sizeof pb.a) == 0};
}

void storeBound(const LaneBound& x, PrimitiveBound& pb) {
  pb.a = simd::vec3Of(x.a);
  pb.b = simd::vec3Of(x.b);
  pb.radius = x.r;
  pb.box.min = simd::vec3Of(x.boxMin);
  pb.box.max = simd::vec3Of(x.boxMax);
}

// x carried through one affine map with a uniformly scaled rotation (scale s >= 0; m: its columns and
// origin) into out, with the float operations of FieldProgram::finishBound's scalar loop lane by lane
// (SpaceMap::worldBounds, toWorld, Bounds::add, intersect). False where that loop must decide (an
// empty or infinite box, a zero bound): out is then unspecified.
bool lift(const LaneBound& x, float s, const glm::vec4* m, LaneBound& out) {
  using namespace simd;
  if (_mm_comigt_ss(x.boxMin, x.boxMax) || !finite3(x.boxMin, x.boxMax)) return false;
  const __m128 c0 = lanes(m[0]), c1 = lanes(m[1]), c2 = lanes(m[2]), o = lanes(m[3]);
  __m128 lo, hi;
  if (!affineWorldBox(c0, c1, c2, o, x.boxMin, x.boxMax, lo, hi)) return false;
  out.point = x.point;
  out.r = x.r * s;
  const __m128 rv = _mm_set1_ps(out.r);
  __m128 capMin, capMax;
  out.a = affineToWorld(c0, c1, c2, o, x.a);
  if (x.point) {  // glm::min(a, a) and glm::max(a, a) are a
    out.b = out.a;
    boxOfTwo(_mm_sub_ps(out.a, rv), _mm_add_ps(out.a, rv), capMin, capMax);
  } else {
    out.b = affineToWorld(c0, c1, c2, o, x.b);
    boxOfTwo(_mm_sub_ps(glmMin(out.a, out.b), rv), _mm_add_ps(glmMax(out.a, out.b), rv), capMin, capMax);
  }
  // intersect(box, capBox), capBox where that is empty.
  const __m128 iMin = glmMax(lo, capMin), iMax = glmMin(hi, capMax);
  const bool empty = _mm_comigt_ss(lo, hi) || _mm_comigt_ss(capMin, capMax) || any3(_mm_cmpgt_ps(iMin, iMax));
  out.boxMin = empty ? capMin : iMin;
  out.boxMax = empty ? capMax : iMax;
  return true;
}
#endif

}  // namespace

PrimitiveBound FieldProgram::worldBound(const glm::vec3& a, const glm::vec3& b, float radius) const {
  PrimitiveBound pb = localBound(a, b, radius);
  finishBound(pb, openMaps_.size());
  return pb;
}

void FieldProgram::carryToWorld(PrimitiveBound* bounds, size_t n) const {
  size_t i = 0;
#if defined(__SSE2__)
  // Two at a time through the maps they share: two independent chains of dependent operations
  // keep the processor busy where one waits on each result.
  for (; i + 1 < n; i += 2) {
    size_t level = openMaps_.size();
    LaneBound x = laneBound(bounds[i]), y = laneBound(bounds[i + 1]);
    for (; level > 0; --level) {
      const float s = openScale_[level - 1];
      const glm::vec4* m = openLanes_.data() + 4 * (level - 1);
      LaneBound nx, ny;
      if (s < 0.0f || !lift(x, s, m, nx) || !lift(y, s, m, ny)) break;
      x = nx;
      y = ny;
    }
    storeBound(x, bounds[i]);
    storeBound(y, bounds[i + 1]);
    finishBound(bounds[i], level);
    finishBound(bounds[i + 1], level);
  }
#endif
  for (; i < n; ++i) finishBound(bounds[i], openMaps_.size());
}

void FieldProgram::finishBound(PrimitiveBound& pb, size_t level) const {
#if defined(__SSE2__)
  // Uniformly scaled rigid maps, the common case, in registers (lift). A level the vector path does
  // not cover (another map, an empty or infinite box, a zero bound) and every level above it take
  // the loop below.
  if (level > 0 && openScale_[level - 1] >= 0.0f) {
    LaneBound x = laneBound(pb);
    for (; level > 0; --level) {
      const float s = openScale_[level - 1];
      LaneBound next;
      if (s < 0.0f || !lift(x, s, openLanes_.data() + 4 * (level - 1), next)) break;
      x = next;
    }
    storeBound(x, pb);
  }
#endif
  while (level-- > 0) {
    const SpaceMap& m = maps[openMaps_[level]];
    Bounds box = m.worldBounds(pb.box);
    const float s = openScale_[level];
    if (s >= 0.0f) {
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
}

bool FieldProgram::pushPrims(PrimClass cls, uint32_t local, bool combineWithPrevious, bool combineMax,
                             const PrimitiveBound& b) {
  uint32_t global = uint32_t(primitiveBounds.size());
  primitiveBounds.push_back(b);
  std::vector<glm::vec3>& colors = classColors[size_t(cls)];
  if (colors.size() <= local) colors.resize(size_t(local) + 1, nextColor);
  colors[local] = nextColor;
  std::vector<FieldOp>& ops = building();
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

PrimitiveBound FieldProgram::pushSkeletal(const SkeletalPrimitive& p) {
  glm::vec3 a, b;
  float r;
  Skeleton s = p.skeleton;
  s.curve = p.skeleton.kind == SkeletonKind::Curve ? curvePoints.data() + p.curveFirst : nullptr;
  skeletonEnclosingCapsule(s, a, b, r);
  skeletal.push_back(p);
  skeletalReach.push_back({a, b, r + std::max(p.radius, 0.0f)});
  return localBound(a, b, r + std::max(p.radius, 0.0f));
}

bool FieldProgram::addSkeletal(const SkeletalPrimitive& p, bool combineWithPrevious, bool combineMax) {
  const uint32_t local = uint32_t(skeletal.size());
  PrimitiveBound bound = pushSkeletal(p);
  carryToWorld(&bound, 1);
  return pushPrims(PrimClass::Skeletal, local, combineWithPrevious, combineMax, bound);
}

bool FieldProgram::addSkeletalRun(const SkeletalPrimitive* p, size_t n, bool combineWithPrevious, bool combineMax) {
  thread_local std::vector<PrimitiveBound> bounds;
  bounds.clear();
  const uint32_t local = uint32_t(skeletal.size());
  for (size_t i = 0; i < n; ++i) bounds.push_back(pushSkeletal(p[i]));
  carryToWorld(bounds.data(), n);
  bool pushed = false;
  for (size_t i = 0; i < n; ++i) {
    const bool added =
        pushPrims(PrimClass::Skeletal, local + uint32_t(i), combineWithPrevious || i > 0, combineMax, bounds[i]);
    if (i == 0) pushed = added;
  }
  return pushed;
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
  building().push_back(op);
}

void FieldProgram::addOperator(OpCode code, uint32_t operands, const float* opParams, int paramCount) {
  FieldOp op;
  op.code = code;
  op.count = operands;
  op.param = uint32_t(params.size());
  for (int i = 0; i < paramCount; ++i) params.push_back(opParams[i]);
  building().push_back(op);
}

void FieldProgram::beginMap(const SpaceMap& m) {
  FieldOp op;
  op.code = OpCode::BeginMap;
  op.first = uint32_t(maps.size());
  openMaps_.push_back(op.first);
  openBegins_.push_back(uint32_t(building().size()));
  float scale;
  openScale_.push_back(m.kind == SpaceMapKind::Affine && uniformScaleRigid(m.forwardLinear, scale) ? scale : -1.0f);
  for (int c = 0; c < 3; ++c) openLanes_.emplace_back(m.forwardLinear[c], 0.0f);
  openLanes_.emplace_back(m.origin, 0.0f);
  maps.push_back(m);
  building().push_back(op);
}

void FieldProgram::endMap() {
  assert(!openMaps_.empty());
  FieldOp op;
  op.code = OpCode::EndMap;
  op.first = openMaps_.back();
  openMaps_.pop_back();
  openBegins_.pop_back();
  openScale_.pop_back();
  openLanes_.resize(openLanes_.size() - 4);
  building().push_back(op);
}

void FieldProgram::reset() {
  threshold = 1.0f;
  ops.clear();
  params.clear();
  maps.clear();
  skeletal.clear();
  skeletalReach.clear();
  curvePoints.clear();
  for (std::vector<float>* v : {&convolution.bx, &convolution.by, &convolution.bz, &convolution.ax, &convolution.ay,
                                &convolution.az, &convolution.length, &convolution.weight, &convolution.sharpness,
                                &convolution.cut2})
    v->clear();
  capsules.clear();
  primitiveBounds.clear();
  for (std::vector<glm::vec3>& c : classColors) c.clear();
  nextColor = srgbToLinear(kClayColorSrgb);
  openMaps_.clear();
  openBegins_.clear();
  openScale_.clear();
  openLanes_.clear();
  outermostEnd_.clear();
  primsBefore_.clear();
  bounds_ = Bounds{};
  unbounded_ = false;
  maxStack_ = 0;
  maxMapDepth_ = 0;
  mapReach_.clear();
  identity_ = 0;
  refillOps_.clear();
  structureDigest_ = 0;
  builtOpCount_ = 0;
  refilling_ = false;
  refillable_ = false;
  structureIdentity_ = 0;
}

void FieldProgram::beginRefill() {
  if (!refillable_) {  // nothing kept: the adds build ops, finishRefill runs finish()
    reset();
    return;
  }
  // reset() with the structure set aside (their memory kept).
  std::vector<FieldOp> keptOps, scratch;
  std::vector<uint32_t> keptEnd, keptBefore;
  keptOps.swap(ops);
  scratch.swap(refillOps_);
  keptEnd.swap(outermostEnd_);
  keptBefore.swap(primsBefore_);
  const uint64_t digest = structureDigest_, structure = structureIdentity_;
  const size_t opCount = builtOpCount_;
  const int stack = maxStack_, mapDepth = maxMapDepth_;
  reset();
  ops.swap(keptOps);
  refillOps_.swap(scratch);
  outermostEnd_.swap(keptEnd);
  primsBefore_.swap(keptBefore);
  structureDigest_ = digest;
  structureIdentity_ = structure;
  builtOpCount_ = opCount;
  maxStack_ = stack;
  maxMapDepth_ = mapDepth;
  refillable_ = true;
  refilling_ = true;
  refillOps_.reserve(builtOpCount_);  // a program seeded by adoptStructure has no scratch memory yet
}

RefillOutcome FieldProgram::finishRefill() {
  if (!refilling_) {
    finish();
    return RefillOutcome::FirstCompile;
  }
  refilling_ = false;
  if (refillOps_.size() == builtOpCount_ && digestOps(refillOps_) == structureDigest_) {
    refillOps_.clear();
    identity_ = nextProgramIdentity();
    runSymbolic();  // the last full finish's ops, which were well formed
    return RefillOutcome::Refilled;
  }
  ops.swap(refillOps_);
  refillOps_.clear();
  finish();
  return RefillOutcome::StructureChanged;
}

void FieldProgram::adoptStructure(const FieldProgram& other) {
  reset();
  if (!other.refillable_) return;
  ops = other.ops;
  outermostEnd_ = other.outermostEnd_;
  primsBefore_ = other.primsBefore_;
  structureDigest_ = other.structureDigest_;
  builtOpCount_ = other.builtOpCount_;
  maxStack_ = other.maxStack_;
  maxMapDepth_ = other.maxMapDepth_;
  structureIdentity_ = other.structureIdentity_;
  refillable_ = true;
}

namespace {

// Where the field of a combining op over n operands (whose supports are boxes[0..n)) can reach the
// threshold: the intersection for Min and RIntersection, the first operand's for Difference, else
// the union (infinite when one is).
Bounds combinedBox(OpCode code, const Bounds* boxes, uint32_t n) {
  Bounds box;
  switch (code) {
    case OpCode::Min:
    case OpCode::RIntersection:
      box = boxes[0];
      for (uint32_t k = 1; k < n; ++k) {
        const Bounds& o = boxes[k];
        if (isInfinite(box)) box = o;
        else if (!isInfinite(o)) box = intersect(box, o);
      }
      break;
    case OpCode::Difference: box = boxes[0]; break;
    default:
      for (uint32_t k = 0; k < n; ++k) {
        if (isInfinite(boxes[k])) box = infiniteBounds();
        if (!isInfinite(box)) box.add(boxes[k]);
      }
  }
  return box;
}

// outermostEnd[i]: the last op of the outermost subtree beginning at op i; primsBefore[i]: the
// primitives in ops[0..i) (global id of the first at or after op i).
void indexSubtrees(const std::vector<FieldOp>& ops, std::vector<uint32_t>& outermostEnd,
                   std::vector<uint32_t>& primsBefore) {
  outermostEnd.assign(ops.size(), 0);
  for (uint32_t i = 0; i < ops.size(); ++i) outermostEnd[i] = i;
  for (uint32_t j = 0; j < ops.size(); ++j) {
    uint32_t b = ops[j].subtreeBegin;
    outermostEnd[b] = std::max(outermostEnd[b], j);
  }
  primsBefore.assign(ops.size() + 1, 0);
  for (uint32_t i = 0; i < ops.size(); ++i)
    primsBefore[i + 1] = primsBefore[i] + (ops[i].code == OpCode::Prims ? ops[i].count : 0);
}

}  // namespace

void FieldProgram::finish() {
  if (refilling_) {  // a refill ended by finish(): its ops are in refillOps_
    (void)finishRefill();
    return;
  }
  identity_ = nextProgramIdentity();
  structureIdentity_ = identity_;
  refilling_ = false;
  refillOps_.clear();
  structureDigest_ = digestOps(ops);
  builtOpCount_ = ops.size();
  foldWideOperators(ops);
  const bool wellFormed = runSymbolic();
  indexSubtrees(ops, outermostEnd_, primsBefore_);
  refillable_ = wellFormed;
  if (!wellFormed) {
    // Empty or malformed program: evaluates to "outside" everywhere.
    ops.clear();
    addConstant(0.0f);
    outermostEnd_.assign(1, 0);
    primsBefore_.assign(2, 0);
    maxStack_ = 1;
    bounds_ = Bounds{};
    unbounded_ = false;
  }
}

bool FieldProgram::runSymbolic() {
  // Empty values, subtree extents and stack depth by a symbolic run (in per-thread memory, kept:
  // a program rebuilt every frame allocates nothing here once warm).
  thread_local std::vector<float> vals;
  thread_local std::vector<uint32_t> begins;
  thread_local std::vector<uint32_t> mapBegins;
  thread_local std::vector<Bounds> boxes;
  thread_local std::vector<Bounds> reach;  // supports under each open map
  vals.clear();
  begins.clear();
  mapBegins.clear();
  boxes.clear();
  reach.clear();
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
        Bounds box = v >= T ? infiniteBounds() : combinedBox(op.code, boxes.data() + base, n);
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
  if (vals.size() != 1) return false;
  unbounded_ = isInfinite(boxes[0]);
  bounds_ = unbounded_ ? Bounds{} : boxes[0];
  return true;
}

}  // namespace animorph
