#pragma once
// Per-region op lists for the GPU polygoniser (docs/gpu-polygonizer.md, "Per-region programs"):
// the CPU's specialisation (FieldProgram::primitivesReaching + specialise) of each program to
// each region of the grid (a superblock of 4^3 blocks), packed as op records into the shaders'
// pool after the whole programs, so that the coarse and fine passes of a block walk only the ops
// and primitives that can matter in its region. Pure C++ (no Vulkan calls): testable without a
// device. Why on the CPU: the whole program's walk is what lavapipe cannot afford (its loop limit,
// and every op's code run under a lane mask), and the CPU's specialise already exists, runs once
// per region (27 regions at 96^3, 64 at 128^3) and costs a few milliseconds for the demo's trees.
#include <cstdint>
#include <vector>

#include "core/field/field_program.h"
#include "core/math/bounds.h"
#include "gpu/polygonizer/gpu_field_program.h"

namespace animorph::gpu {

struct RegionOpLists {
  uint32_t table = 0;      // pool index: one uvec4 per region, (opBegin A, opCount A, opBegin B, opCount B)
  uint32_t masks = 0;      // with masks: pool index; region r's mask word w is word (r * maskWords + w) from masks * 4
  uint32_t maskWords = 0;  // words of a primitive mask ((primitives + 31) / 32)
  uint32_t regions = 0;
  uint32_t longestOps = 0;  // the longest list (both programs together)
  uint64_t opsTotal = 0;    // all lists' ops together
  // Shader loop iterations of one invocation (as gpuLoopIterationEstimate counts them for a whole
  // program), the most over the regions: an interval walk of a list and the mask words (the
  // coarse pass of a superblock); the coarse pass of a block (its candidates then the interval);
  // the fine passes (sub-block intervals and corners, the normals' stencil).
  uint64_t longestIntervalWalk = 0, longestCoarse = 0, longestFine = 0;
  // The normals pass's walk of one list for one vertex (the stencil's pair or the analytic gradient):
  // the fine figure above counts it once (the pass run once per vertex where needed).
  uint64_t longestNormalWalk = 0;
  // The colour pass's walk of one list for one vertex (shaders/include/poly_color_main.glsl: every op,
  // every primitive of a Prims op one by one, operators' operands, the kernels reaching the region),
  // the most over the regions: what GpuPolygonizer compares with the loop limit before colouring.
  uint64_t longestColorWalk = 0;
  bool stencilNormals = false;  // the programs' normals take the stencil (two walks for four vertices)
  std::vector<uint64_t> intervalWalk;  // per region: the first figure
  // Per program (a, b), per region: the primitives (program-local ids) reaching it, sorted.
  std::vector<std::vector<uint32_t>> reaching[2];
};

// Appends to pk.pool (pk packed from a and b by packFieldPrograms) one op list per program and
// region, with masks the regions' primitive masks over global ids (a's primitives, then b's), and
// the table of lists. A primitive is in region r's mask, and its subtree in r's lists, when its
// bound reaches regions[r] (the caller grows each box by what the passes read beyond it). With
// parent, region r lies inside parent's region parentOf[r], whose reaching primitives are the
// only candidates. Values inside a region are those of the whole program: the primitives left out
// contribute exactly 0 there.
// For the colour pass each list op carries what the CPU's colour walk reads beside it
// (field/surface_color.h): op1.w the colour provenance specialise left in the op's subtreeBegin
// (a dropped subtree's or operand's empty colour, by the whole program's op index); a Prims op's
// op1.y the global id of its whole op's first primitive (its colour where none contributes); a
// BeginMap's op0.z its map index (the map's empty colour). The field passes read none of these.
RegionOpLists appendRegionOpLists(const FieldProgram& a, const FieldProgram* b, const std::vector<Bounds>& regions,
                                  PackedFieldPrograms& pk, bool masks, const RegionOpLists* parent = nullptr,
                                  const std::vector<uint32_t>* parentOf = nullptr);

}  // namespace animorph::gpu
