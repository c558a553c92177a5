#include "gpu/polygonizer/gpu_region_op_lists.h"

#include <algorithm>
#include <bit>

#include "poly_constants.h"

namespace animorph::gpu {

namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

// One program's side of the lists: where its records are, and the class-local index of each of its
// primitives (a specialised Prims op lists class-local indices; the shaders want global ids).
struct ProgramSide {
  const FieldProgram& prog;
  uint32_t paramsBase, mapsBase, classBase[3];
  uint32_t primOffset;            // global id of its first primitive
  std::vector<uint32_t> localOf;  // by program-local global id
  std::vector<uint8_t> kernelLoops;    // by program-local global id: loop iterations of its kernel at 8 points
  std::vector<uint8_t> gradientLoops;  // the same for its value and gradient at 4 points (the normals)
  std::vector<uint8_t> intervalLoops;  // the same for its interval (the potential's power, twice)
  // The colour pass's kernel at one point beyond its step of the Prims loop: a spline curve's
  // closest point (16 samples per span, 8 refinement steps: poly_field.glsl closestOnCurve), else none.
  std::vector<uint32_t> colorLoops;

  ProgramSide(const FieldProgram& p, const PackedFieldPrograms& pk, int which)
      : prog(p), paramsBase(pk.paramsBase[which]), mapsBase(pk.mapsBase[which]),
        classBase{pk.classBase[which][0], pk.classBase[which][1], pk.classBase[which][2]},
        primOffset(pk.primBegin[which]), localOf(p.primitiveCount(), 0u), kernelLoops(p.primitiveCount(), 1u),
        gradientLoops(p.primitiveCount(), 1u), intervalLoops(p.primitiveCount(), 1u),
        colorLoops(p.primitiveCount(), 0u) {
    for (const FieldOp& op : p.ops)
      if (op.code == OpCode::Prims)
        for (uint32_t k = 0; k < op.count; ++k) {
          localOf[op.primBegin + k] = op.first + k;
          // A skeletal or capsule kernel: one step of the op's loop, then its loop over the 8 points
          // four at a time (2 steps; the normals' 4 points: 1; the power has no loop); a spline
          // curve's closest point loops over its segments and 8 refinement steps per point. A
          // convolution segment: one step.
          const bool conv = op.primClass == PrimClass::Convolution;
          uint32_t loops = conv ? 1u : 3u, gradient = conv ? 1u : 2u, intervalSteps = 1u;
          if (op.primClass == PrimClass::Skeletal) {
            const Skeleton& sk = p.skeletal[op.first + k].skeleton;
            if (sk.kind == SkeletonKind::Curve) {
              intervalSteps = uint32_t(std::min(200, sk.curveCount + 10));
              colorLoops[op.primBegin + k] = 16u * uint32_t(std::max(sk.curveCount - 1, 0)) + 10u;
              loops = std::min(255u, 8u * intervalSteps + 3u);
              gradient = std::min(255u, 4u * intervalSteps + 2u);
            }
          }
          kernelLoops[op.primBegin + k] = uint8_t(loops);
          gradientLoops[op.primBegin + k] = uint8_t(gradient);
          intervalLoops[op.primBegin + k] = uint8_t(std::min(255u, intervalSteps));
        }
  }
};

uint32_t recordSize(PrimClass c) {
  return c == PrimClass::Convolution ? AM_REC_CONV : c == PrimClass::Skeletal ? AM_REC_SKEL : AM_REC_CAPSULE;
}

// Loop iterations of one walk of a list, as gpuLoopIterationEstimate counts a whole program's.
struct ListLoops {
  uint64_t value = 0, interval = 0, color = 0;  // color: the colour pass's walk (poly_color_main.glsl)
};

// The op records of act (side's program specialised to one region) appended to pool, in the
// format of packFieldPrograms: a Prims op covers the span of its active primitives (the others in
// the span are skipped by the block masks); a BeginMap skips to its own EndMap when none of its
// primitives reaches a block.
ListLoops packActive(const ProgramSide& side, const ActiveProgram& act, std::vector<glm::uvec4>& pool) {
  ListLoops loops;
  const uint32_t base = uint32_t(pool.size());
  pool.resize(base + AM_REC_OP * act.ops.size(), glm::uvec4(0u));
  struct OpenMap {
    uint32_t at, p0, p1;  // list index; global primitive range of its subtree so far
  };
  std::vector<OpenMap> open;
  for (uint32_t j = 0; j < act.ops.size(); ++j) {
    const FieldOp& op = act.ops[j];
    glm::uvec4 op0(uint32_t(op.code), 0u, op.count, 0u);
    // op1.w: the colour provenance (the region op lists' contract in gpu_region_op_lists.h).
    glm::uvec4 op1(side.paramsBase * 4u + op.param, 0u, bits(op.emptyValue), op.subtreeBegin);
    loops.value += 1;
    loops.interval += 1;
    loops.color += 1;
    if (op.code == OpCode::Prims) {
      uint32_t lo = side.localOf.empty() ? 0u : side.localOf[op.primBegin], n = 0;
      if (op.count > 0) {
        const uint32_t first = act.indices[op.first], lastIdx = act.indices[op.first + op.count - 1];
        n = lastIdx - first + 1;
        lo = first;
      }
      const uint32_t g0 = op.primBegin + (lo - (side.localOf.empty() ? 0u : side.localOf[op.primBegin]));
      op0.x |= uint32_t(op.primClass) << 8 | (op.combineMax ? 1u : 0u) << 16;
      op0.y = side.classBase[uint32_t(op.primClass)] + recordSize(op.primClass) * lo;
      op0.z = n;
      op0.w = side.primOffset + g0;
      op1.y = side.primOffset + op.primBegin;  // the colour where none contributes: the whole op's first
      loops.color += n;
      if (op.primClass == PrimClass::Convolution) {
        loops.value += n / 32 + 2;
      } else {
        loops.value += n;
        loops.interval += n;
      }
      if (!open.empty() && n > 0) {
        open.back().p0 = std::min(open.back().p0, g0);
        open.back().p1 = std::max(open.back().p1, g0 + n);
      }
    } else if (op.code == OpCode::BeginMap || op.code == OpCode::EndMap) {
      op1.y = side.mapsBase + AM_REC_MAP * op.first;
      if (op.code == OpCode::BeginMap) op0.z = op.first;  // the colour pass's map empty colour
    } else if (op.code != OpCode::Const) {
      loops.value += uint64_t(AM_POLY_CORNER_V) * (op.count + 1);
      loops.interval += op.count + 1;
      loops.color += 3 * uint64_t(op.count);
    }
    pool[base + AM_REC_OP * j] = op0;
    pool[base + AM_REC_OP * j + 1] = op1;
    if (op.code == OpCode::BeginMap) open.push_back({j, UINT32_MAX, 0u});
    if (op.code == OpCode::EndMap && !open.empty()) {
      const OpenMap m = open.back();
      open.pop_back();
      const uint32_t p0 = m.p0 == UINT32_MAX ? 0u : m.p0, p1 = m.p0 == UINT32_MAX ? 0u : m.p1;
      glm::uvec4& b0 = pool[base + AM_REC_OP * m.at];
      glm::uvec4& b1 = pool[base + AM_REC_OP * m.at + 1];
      b0.w = side.primOffset + p0;
      b0.y = p1 - p0;
      b1.z = bits(op.emptyValue);  // the map's subtree where none of its primitives contributes
      b1.w = j - m.at;             // (a BeginMap carries no colour provenance: its op1.w is the skip)
      // The interpreters test the subtree's mask words at the BeginMap (anyPrimActive): a loop.
      const uint64_t maskSteps = p1 > p0 ? ((p1 - 1) >> 5) - (p0 >> 5) + 1 : 1;
      loops.value += maskSteps;
      loops.interval += maskSteps;
      loops.color += maskSteps;
      if (!open.empty() && m.p0 != UINT32_MAX) {
        open.back().p0 = std::min(open.back().p0, p0);
        open.back().p1 = std::max(open.back().p1, p1);
      }
    }
  }
  return loops;
}

// Whether the normals pass takes p's analytic gradient (AM_ANALYTIC_GRADIENT in
// poly_field_gradient.glsl: no HyperBlend, affine maps only) rather than the tetrahedral stencil.
bool analyticGradients(const FieldProgram& p) {
  for (const FieldOp& op : p.ops)
    if (op.code == OpCode::HyperBlend) return false;
  for (const SpaceMap& m : p.maps)
    if (m.kind != SpaceMapKind::Affine) return false;
  return true;
}

}  // namespace

RegionOpLists appendRegionOpLists(const FieldProgram& a, const FieldProgram* b, const std::vector<Bounds>& regions,
                                  PackedFieldPrograms& pk, bool masks, const RegionOpLists* parent,
                                  const std::vector<uint32_t>* parentOf) {
  RegionOpLists out;
  out.regions = uint32_t(regions.size());
  out.maskWords = std::max(1u, (pk.primitiveTotal() + 31) / 32);
  std::vector<glm::uvec4>& pool = pk.pool;
  out.table = uint32_t(pool.size());
  pool.resize(pool.size() + regions.size(), glm::uvec4(0u));
  if (masks) {
    out.masks = uint32_t(pool.size());
    pool.resize(pool.size() + (size_t(out.maskWords) * regions.size() + 3) / 4, glm::uvec4(0u));
  }
  std::vector<ProgramSide> sides;
  sides.emplace_back(a, pk, 0);
  if (b) sides.emplace_back(*b, pk, 1);
  const bool stencilNormals = !analyticGradients(a) || (b && !analyticGradients(*b));
  out.stencilNormals = stencilNormals;
  const uint64_t words = out.maskWords;
  ActiveProgram act;
  for (size_t k = 0; k < sides.size(); ++k) out.reaching[k].resize(regions.size());
  for (uint32_t r = 0; r < regions.size(); ++r) {
    glm::uvec4 entry(0u);
    ListLoops total;
    uint64_t candidates = 0, kernels = 0, gradientKernels = 0, intervalKernels = 0, colorKernels = 0;
    for (size_t k = 0; k < sides.size(); ++k) {
      const ProgramSide& side = sides[k];
      std::vector<uint32_t>& reaching = out.reaching[k][r];
      const std::vector<uint32_t>* within = parent ? &parent->reaching[k][(*parentOf)[r]] : nullptr;
      side.prog.primitivesReaching(regions[r], reaching, within);
      candidates += within ? within->size() : reaching.size();
      for (uint32_t g : reaching) {
        kernels += side.kernelLoops[g];
        gradientKernels += side.gradientLoops[g];
        intervalKernels += side.intervalLoops[g];
        colorKernels += side.colorLoops[g];
      }
      if (masks)
        for (uint32_t g : reaching) {
          const uint64_t word = out.masks * 4ull + r * words + (side.primOffset + g) / 32;
          pool[word / 4][int(word % 4)] |= 1u << ((side.primOffset + g) % 32);
        }
      side.prog.specialise(reaching, act);
      const uint32_t begin = uint32_t(pool.size());
      const ListLoops l = packActive(side, act, pool);
      total.value += l.value;
      total.interval += l.interval;
      total.color += l.color;
      entry[int(2 * k)] = begin;
      entry[int(2 * k + 1)] = uint32_t(act.ops.size());
      out.opsTotal += act.ops.size();
    }
    pool[out.table + r] = entry;
    out.longestOps = std::max(out.longestOps, entry.y + entry.w);
    // As gpuLoopIterationEstimate: the coarse pass (mask words, candidates, interval), the cells pass
    // (the sub-block intervals and the corners in SIMD groups of their own, bookkeeping), the normals
    // (one vertex's walk: the stencil's pair, or the analytic gradient).
    // The kernels of every primitive reaching the region count too: a block of it may be reached by all.
    const uint64_t interval = total.interval + intervalKernels;
    out.intervalWalk.push_back(3 * words + 32 + interval);
    out.longestIntervalWalk = std::max(out.longestIntervalWalk, out.intervalWalk.back());
    out.longestCoarse = std::max(out.longestCoarse, 3 * words + candidates + 32 + interval);
    const uint64_t normals = stencilNormals ? total.value + kernels + 16 : total.value + gradientKernels + 16;
    out.longestNormalWalk = std::max(out.longestNormalWalk, normals);
    out.longestColorWalk = std::max(out.longestColorWalk, total.color + colorKernels + 16);
    out.longestFine = std::max({out.longestFine, interval + 512, total.value + kernels + 512, normals});
  }
  return out;
}

}  // namespace animorph::gpu
