#pragma once
// One or two FieldPrograms packed for the GPU polygoniser's shaders
// (shaders/include/poly_field*.glsl): ops, operator parameters, space maps,
// primitive records and spline control points in one pool of 16-byte words,
// plus a bound per primitive for the per-block primitive lists. Pure C++ (no
// Vulkan calls), so packing and its limits are testable without a device.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/field/field_program.h"
#include "core/util/result.h"

namespace animorph::gpu {

struct PackedFieldPrograms {
  std::vector<glm::uvec4> pool;    // the shaders' `pool` (floats stored as their bits)
  std::vector<glm::vec4> bounds;   // AM_REC_BOUND vec4 per primitive, program A's then B's
  uint32_t programCount = 1;
  uint32_t opBegin[2] = {0, 0};    // first op record (index into pool)
  uint32_t opCount[2] = {0, 0};
  uint32_t primBegin[2] = {0, 0};  // first global primitive id
  uint32_t primCount[2] = {0, 0};
  float threshold[2] = {1.0f, 1.0f};
  // What the programs use, for the shaders' specialisation (poly_constants.h):
  // AM_FEAT_OP_BIT / AM_FEAT_CLASS_BIT bits, and AM_KIND_SKEL_BIT / AM_KIND_MAP_BIT bits.
  uint32_t features = 0;
  uint32_t kinds = 0;
  // Where each program's records start in the pool: operator parameters (in floats: 4 a word),
  // maps, and the primitives of each PrimClass. Op lists packed later (appendRegionOpLists) point
  // into the same records.
  uint32_t paramsBase[2] = {0, 0};
  uint32_t mapsBase[2] = {0, 0};
  uint32_t classBase[2][3] = {{0, 0, 0}, {0, 0, 0}};
  uint32_t primitiveTotal() const { return primCount[0] + primCount[1]; }
};

// Why the GPU cannot evaluate program (empty when it can): names the feature and
// the limit, e.g. "operator stack depth 20 exceeds the GPU limit 16". Callers fall
// back to the CPU polygoniser when it is not empty.
std::string gpuUnsupportedReason(const FieldProgram& program);

// The loop iterations one invocation of a field pass (coarse, corners + cells, normals) runs for
// a and b (b may be null), all loops counted together, in the part that culling does not change:
// every op walked (an unreached map subtree is skipped in one step, so the walk may be shorter),
// every primitive of a skeletal or capsule run stepped over, operators' operands, the coarse
// pass's primitive lists. The kernels of the primitives reaching a block add to it. lavapipe
// stops a shader invocation's loops past AM_POLY_LLVMPIPE_LOOP_LIMIT (poly_constants.h): programs
// estimated above it are walked per region there (gpu_region_op_lists.h), or refused up front when
// region programs are off; the passes detect the rest (AM_OVERFLOW_LOOPS).
uint64_t gpuLoopIterationEstimate(const FieldProgram& a, const FieldProgram* b = nullptr);

// What packFieldPrograms(a, b) gives for the pipeline variant, without packing: its features and
// kinds bits and its pool's size in 16-byte words. Costs a walk over the ops, maps and skeletal
// primitives (no pool is written): what GpuPolygonizer::ready and prewarm need every frame.
struct FieldProgramsShape {
  uint32_t features = 0, kinds = 0;
  size_t poolWords = 0;
};
FieldProgramsShape fieldProgramsShape(const FieldProgram& a, const FieldProgram* b = nullptr);

// Packs a (and b, when non-null) for the shaders. Errors: gpuUnsupportedReason's,
// prefixed with "program A"/"program B".
Result<PackedFieldPrograms> packFieldPrograms(const FieldProgram& a, const FieldProgram* b = nullptr);

}  // namespace animorph::gpu
