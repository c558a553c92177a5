#include "gpu/polygonizer/gpu_field_program.h"

#include <algorithm>
#include <bit>

#include "core/field/skeleton.h"
#include "poly_constants.h"

namespace animorph::gpu {

static_assert(uint32_t(OpCode::Prims) == AM_OP_PRIMS && uint32_t(OpCode::Const) == AM_OP_CONST &&
              uint32_t(OpCode::Sum) == AM_OP_SUM && uint32_t(OpCode::Max) == AM_OP_MAX &&
              uint32_t(OpCode::Min) == AM_OP_MIN && uint32_t(OpCode::HyperBlend) == AM_OP_HYPERBLEND &&
              uint32_t(OpCode::Difference) == AM_OP_DIFFERENCE && uint32_t(OpCode::RUnion) == AM_OP_RUNION &&
              uint32_t(OpCode::RIntersection) == AM_OP_RINTERSECTION &&
              uint32_t(OpCode::BoundedBlend) == AM_OP_BOUNDEDBLEND && uint32_t(OpCode::BeginMap) == AM_OP_BEGINMAP &&
              uint32_t(OpCode::EndMap) == AM_OP_ENDMAP && uint32_t(OpCode::Remap) == AM_OP_REMAP,
              "op codes of poly_constants.h must match animorph::OpCode");
static_assert(uint32_t(PrimClass::Skeletal) == AM_PRIM_SKELETAL &&
              uint32_t(PrimClass::Convolution) == AM_PRIM_CONVOLUTION &&
              uint32_t(PrimClass::Capsule) == AM_PRIM_CAPSULE);
static_assert(uint32_t(SkeletonKind::Point) == AM_SKEL_POINT && uint32_t(SkeletonKind::Sphere) == AM_SKEL_SPHERE &&
              uint32_t(SkeletonKind::Segment) == AM_SKEL_SEGMENT &&
              uint32_t(SkeletonKind::Cylinder) == AM_SKEL_CYLINDER && uint32_t(SkeletonKind::Cone) == AM_SKEL_CONE &&
              uint32_t(SkeletonKind::Disc) == AM_SKEL_DISC && uint32_t(SkeletonKind::Circle) == AM_SKEL_CIRCLE &&
              uint32_t(SkeletonKind::Triangle) == AM_SKEL_TRIANGLE && uint32_t(SkeletonKind::Curve) == AM_SKEL_CURVE);
static_assert(uint32_t(SpaceMapKind::Affine) == AM_MAP_AFFINE && uint32_t(SpaceMapKind::Twist) == AM_MAP_TWIST &&
              uint32_t(SpaceMapKind::Taper) == AM_MAP_TAPER && uint32_t(SpaceMapKind::Bend) == AM_MAP_BEND);

namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

glm::uvec4 words(const glm::vec3& v, float w) { return {bits(v.x), bits(v.y), bits(v.z), bits(w)}; }
glm::uvec4 words(const glm::vec3& v, uint32_t w) { return {bits(v.x), bits(v.y), bits(v.z), w}; }
glm::uvec4 words(float x, float y, float z, float w) { return {bits(x), bits(y), bits(z), bits(w)}; }

void packOne(const FieldProgram& prog, uint32_t primOffset, PackedFieldPrograms& out, int which) {
  std::vector<glm::uvec4>& pool = out.pool;
  const uint32_t opsBase = uint32_t(pool.size());
  const uint32_t paramsBase = opsBase + AM_REC_OP * uint32_t(prog.ops.size());
  const uint32_t mapsBase = paramsBase + uint32_t((prog.params.size() + 3) / 4);
  const uint32_t convBase = mapsBase + AM_REC_MAP * uint32_t(prog.maps.size());
  const uint32_t skelBase = convBase + AM_REC_CONV * uint32_t(prog.convolution.size());
  const uint32_t capBase = skelBase + AM_REC_SKEL * uint32_t(prog.skeletal.size());
  const uint32_t curveBase = capBase + AM_REC_CAPSULE * uint32_t(prog.capsules.size());
  const uint32_t end = curveBase + uint32_t(prog.curvePoints.size());
  pool.resize(end, glm::uvec4(0u));

  for (size_t i = 0; i < prog.ops.size(); ++i) {
    const FieldOp& op = prog.ops[i];
    out.features |= AM_FEAT_OP_BIT(uint32_t(op.code));
    if (op.code == OpCode::Prims) out.features |= AM_FEAT_CLASS_BIT(uint32_t(op.primClass));
    glm::uvec4 op0(uint32_t(op.code), 0u, op.count, 0u);
    glm::uvec4 op1(paramsBase * 4u + op.param, 0u, bits(op.emptyValue), 0u);
    if (op.code == OpCode::Prims) {
      op0.x |= uint32_t(op.primClass) << 8 | (op.combineMax ? 1u : 0u) << 16;
      uint32_t base = op.primClass == PrimClass::Convolution ? convBase + AM_REC_CONV * op.first
                      : op.primClass == PrimClass::Skeletal  ? skelBase + AM_REC_SKEL * op.first
                                                             : capBase + AM_REC_CAPSULE * op.first;
      op0.y = base;
      op0.w = primOffset + op.primBegin;
    } else if (op.code == OpCode::BeginMap || op.code == OpCode::EndMap) {
      op1.y = mapsBase + AM_REC_MAP * op.first;
    }
    if (op.code == OpCode::BeginMap) {
      // The subtree this map opens (ops i..e, one value): its primitives' global ids [p0, p1) and
      // how many ops to skip, so that a block none of them reaches pushes ops[e].emptyValue instead
      // of running the subtree (as FieldProgram::specialise does on the CPU).
      const uint32_t e = prog.subtreeEnd(uint32_t(i));
      uint32_t p0 = UINT32_MAX, p1 = 0;
      for (uint32_t k = uint32_t(i); k <= e; ++k)
        if (prog.ops[k].code == OpCode::Prims && prog.ops[k].count > 0) {
          p0 = std::min(p0, prog.ops[k].primBegin);
          p1 = std::max(p1, prog.ops[k].primBegin + prog.ops[k].count);
        }
      if (p0 == UINT32_MAX) p0 = p1 = 0;
      op0.w = primOffset + p0;
      op0.y = p1 - p0;
      op1.z = bits(prog.ops[e].emptyValue);
      op1.w = e - uint32_t(i);
    }
    pool[opsBase + AM_REC_OP * i] = op0;
    pool[opsBase + AM_REC_OP * i + 1] = op1;
  }
  for (size_t i = 0; i < prog.params.size(); ++i) pool[paramsBase + i / 4][int(i % 4)] = bits(prog.params[i]);
  for (size_t i = 0; i < prog.maps.size(); ++i) {
    const SpaceMap& m = prog.maps[i];
    out.kinds |= AM_KIND_MAP_BIT(uint32_t(m.kind));
    uint32_t r = mapsBase + AM_REC_MAP * uint32_t(i);
    pool[r] = words(m.linear[0], uint32_t(m.kind));
    pool[r + 1] = words(m.linear[1], m.length);
    pool[r + 2] = words(m.linear[2], m.k0);
    pool[r + 3] = words(m.origin, m.k1);
  }
  const ConvolutionData& c = prog.convolution;
  for (size_t i = 0; i < c.size(); ++i) {
    uint32_t r = convBase + AM_REC_CONV * uint32_t(i);
    pool[r] = words(c.bx[i], c.by[i], c.bz[i], c.length[i]);
    pool[r + 1] = words(c.ax[i], c.ay[i], c.az[i], c.weight[i]);
    pool[r + 2] = words(c.sharpness[i], c.cut2[i], 0.0f, 0.0f);
  }
  for (size_t i = 0; i < prog.skeletal.size(); ++i) {
    const SkeletalPrimitive& p = prog.skeletal[i];
    Skeleton s = p.skeleton;
    out.kinds |= AM_KIND_SKEL_BIT(uint32_t(s.kind));
    if (s.kind == SkeletonKind::Curve) s.curve = prog.curvePoints.data() + p.curveFirst;
    glm::vec3 ca, cb;
    float cr;
    skeletonEnclosingCapsule(s, ca, cb, cr);
    uint32_t r = skelBase + AM_REC_SKEL * uint32_t(i);
    uint32_t curveCount = s.kind == SkeletonKind::Curve ? uint32_t(std::max(0, s.curveCount)) : 0u;
    pool[r] = words(s.p0, uint32_t(s.kind) | curveCount << 8);
    pool[r + 1] = words(s.p1, s.r0);
    pool[r + 2] = words(s.p2, s.r1);
    pool[r + 3] = glm::uvec4(bits(p.radius), bits(p.intensity), bits(p.stiffness), curveBase + p.curveFirst);
    pool[r + 4] = words(ca, cr + p.radius);
    pool[r + 5] = words(cb, 0.0f);
  }
  for (size_t i = 0; i < prog.capsules.size(); ++i) {
    const CapsulePrimitive& cp = prog.capsules[i];
    uint32_t r = capBase + AM_REC_CAPSULE * uint32_t(i);
    pool[r] = words(cp.a, cp.radius);
    pool[r + 1] = words(cp.b, 0.0f);
  }
  for (size_t i = 0; i < prog.curvePoints.size(); ++i) pool[curveBase + i] = words(prog.curvePoints[i], 0.0f);

  for (const PrimitiveBound& b : prog.primitiveBounds) {
    out.bounds.push_back(glm::vec4(b.a, b.radius));
    out.bounds.push_back(glm::vec4(b.b, 0.0f));
    out.bounds.push_back(glm::vec4(b.box.min, 0.0f));
    out.bounds.push_back(glm::vec4(b.box.max, 0.0f));
  }
  out.opBegin[which] = opsBase;
  out.opCount[which] = uint32_t(prog.ops.size());
  out.paramsBase[which] = paramsBase;
  out.mapsBase[which] = mapsBase;
  out.classBase[which][AM_PRIM_SKELETAL] = skelBase;
  out.classBase[which][AM_PRIM_CONVOLUTION] = convBase;
  out.classBase[which][AM_PRIM_CAPSULE] = capBase;
  out.primBegin[which] = primOffset;
  out.primCount[which] = uint32_t(prog.primitiveCount());
  out.threshold[which] = prog.threshold;
}

}  // namespace

std::string gpuUnsupportedReason(const FieldProgram& program) {
  if (program.maxStack() > AM_POLY_MAX_STACK)
    return "operator stack depth " + std::to_string(program.maxStack()) + " exceeds the GPU limit " +
           std::to_string(AM_POLY_MAX_STACK) + " (operators nested too deep)";
  if (program.maxMapDepth() > AM_POLY_MAX_MAP_DEPTH)
    return "space maps nested " + std::to_string(program.maxMapDepth()) + " deep exceed the GPU limit " +
           std::to_string(AM_POLY_MAX_MAP_DEPTH);
  for (const SkeletalPrimitive& p : program.skeletal)
    if (p.skeleton.kind == SkeletonKind::Curve && p.skeleton.curveCount > 0xffffff)
      return "a spline-curve primitive with " + std::to_string(p.skeleton.curveCount) + " control points";
  return {};
}

namespace {

// Loop iterations of one evaluation of a program by the shaders' interpreters that do not depend
// on which primitives reach the block (poly_field_program.glsl for values, poly_field.glsl for
// intervals; the gradient's walk is the values').
struct ProgramLoops {
  uint64_t value = 0, interval = 0;
};

ProgramLoops programLoops(const FieldProgram& p) {
  ProgramLoops c;
  for (const FieldOp& op : p.ops) {
    c.value += 1;  // the op loop
    c.interval += 1;
    if (op.code == OpCode::Prims) {
      if (op.primClass == PrimClass::Convolution) {
        c.value += op.count / 32 + 2;  // the mask words (then only the set bits)
      } else {
        c.value += op.count;  // every primitive of the run is stepped over (then the active ones' kernels)
        c.interval += op.count;
      }
    } else if (op.code != OpCode::Const && op.code != OpCode::BeginMap && op.code != OpCode::EndMap) {
      c.value += uint64_t(AM_POLY_CORNER_V) * (op.count + 1);  // per point vec4, per operand
      c.interval += op.count + 1;
    }
  }
  return c;
}

}  // namespace

uint64_t gpuLoopIterationEstimate(const FieldProgram& a, const FieldProgram* b) {
  ProgramLoops c = programLoops(a);
  uint64_t total = a.primitiveCount();
  if (b) {
    ProgramLoops cb = programLoops(*b);
    c.value += cb.value;
    c.interval += cb.interval;
    total += b->primitiveCount();
  }
  const uint64_t words = (total + 31) / 32;
  const uint64_t coarse = total + 2 * words + 32 + c.interval;  // primitive lists, then the interval
  const uint64_t cells = std::max(c.interval, c.value) + 512;  // sub-block intervals | corners (own SIMD groups)
  const uint64_t normals = 2 * c.value + 16;                    // the stencil: two evaluations
  return std::max({coarse, cells, normals});
}

FieldProgramsShape fieldProgramsShape(const FieldProgram& a, const FieldProgram* b) {
  FieldProgramsShape out;
  for (const FieldProgram* p : {&a, b}) {
    if (!p) continue;
    for (const FieldOp& op : p->ops) {
      out.features |= AM_FEAT_OP_BIT(uint32_t(op.code));
      if (op.code == OpCode::Prims) out.features |= AM_FEAT_CLASS_BIT(uint32_t(op.primClass));
    }
    for (const SpaceMap& m : p->maps) out.kinds |= AM_KIND_MAP_BIT(uint32_t(m.kind));
    for (const SkeletalPrimitive& sp : p->skeletal) out.kinds |= AM_KIND_SKEL_BIT(uint32_t(sp.skeleton.kind));
    // packOne's layout: ops, params (4 a word), maps, convolution, skeletal, capsule records, curve points.
    out.poolWords += AM_REC_OP * p->ops.size() + (p->params.size() + 3) / 4 + AM_REC_MAP * p->maps.size() +
                     AM_REC_CONV * p->convolution.size() + AM_REC_SKEL * p->skeletal.size() +
                     AM_REC_CAPSULE * p->capsules.size() + p->curvePoints.size();
  }
  out.poolWords = std::max<size_t>(out.poolWords, 1);  // packFieldPrograms never leaves the pool empty
  return out;
}

Result<PackedFieldPrograms> packFieldPrograms(const FieldProgram& a, const FieldProgram* b) {
  if (std::string why = gpuUnsupportedReason(a); !why.empty()) return Error{"program A: " + why};
  if (b)
    if (std::string why = gpuUnsupportedReason(*b); !why.empty()) return Error{"program B: " + why};
  PackedFieldPrograms out;
  out.programCount = b ? 2 : 1;
  packOne(a, 0, out, 0);
  if (b) packOne(*b, uint32_t(a.primitiveCount()), out, 1);
  if (out.pool.empty()) out.pool.push_back(glm::uvec4(0u));
  if (out.bounds.empty()) out.bounds.resize(AM_REC_BOUND, glm::vec4(0.0f));
  return out;
}

}  // namespace animorph::gpu
