// Declarations shared by the polygoniser's compute shaders (engine/gpu/polygonizer/gpu_polygonizer.cpp):
// per-frame parameters, the primitive/op pool, block data and helpers for the
// block grid and edge numbering. Buffers a shader does not use are still
// declared; the compiler drops them.
#include "poly_constants.h"

// (Only bit tests on the constants: glslang 12 emits invalid SPIR-V for logical
// operators applied to specialisation-constant booleans, so negations and
// alternatives are written as one mask test.)
// What this pipeline variant evaluates (poly_constants.h, AM_FEAT_* / AM_KIND_*):
// set at pipeline creation by gpu_polygonizer.cpp; all bits (the default) is the
// generic interpreter. Tests of a feature are constant after specialisation, so
// the code of what a program does not use is removed.
layout(constant_id = 0) const uint kAmFeatures = AM_FEAT_ALL;
layout(constant_id = 1) const uint kAmKinds = AM_FEAT_ALL;
#define AM_HAS_OP(c) ((kAmFeatures & AM_FEAT_OP_BIT(c)) != 0u)
#define AM_HAS_CLASS(k) ((kAmFeatures & AM_FEAT_CLASS_BIT(k)) != 0u)
#define AM_HAS_COMBINE(m) ((kAmFeatures & AM_FEAT_COMBINE_BIT(m)) != 0u)
#define AM_HAS_SKEL(k) ((kAmKinds & AM_KIND_SKEL_BIT(k)) != 0u)
#define AM_HAS_MAP(k) ((kAmKinds & AM_KIND_MAP_BIT(k)) != 0u)
// Any n-ary operator (Sum .. BoundedBlend, Remap); maps; whether programs need the operand stack at all
// (a program of one Prims op and nothing else does not).
#define AM_FEAT_OPERATORS                                                                                          \
  (AM_FEAT_OP_BIT(AM_OP_SUM) | AM_FEAT_OP_BIT(AM_OP_MAX) | AM_FEAT_OP_BIT(AM_OP_MIN) | AM_FEAT_OP_BIT(AM_OP_HYPERBLEND) | \
   AM_FEAT_OP_BIT(AM_OP_DIFFERENCE) | AM_FEAT_OP_BIT(AM_OP_RUNION) | AM_FEAT_OP_BIT(AM_OP_RINTERSECTION) |               \
   AM_FEAT_OP_BIT(AM_OP_BOUNDEDBLEND) | AM_FEAT_OP_BIT(AM_OP_REMAP))
#define AM_HAS_OPERATORS ((kAmFeatures & AM_FEAT_OPERATORS) != 0u)
#define AM_STACKLESS                                                                                                     \
  ((kAmFeatures & (AM_FEAT_OPERATORS | AM_FEAT_OP_BIT(AM_OP_BEGINMAP) | AM_FEAT_OP_BIT(AM_OP_ENDMAP) |                   \
                   AM_FEAT_OP_BIT(AM_OP_CONST))) == 0u)
// Only one program (no morph); no spatially varying map (every map is affine); no curve skeletons.
#define AM_SINGLE_ONLY \
  ((kAmFeatures & (AM_FEAT_COMBINE_BIT(AM_COMBINE_INTERPOLATE) | AM_FEAT_COMBINE_BIT(AM_COMBINE_SPACETIME))) == 0u)
#define AM_AFFINE_MAPS_ONLY \
  ((kAmKinds & (AM_KIND_MAP_BIT(AM_MAP_TWIST) | AM_KIND_MAP_BIT(AM_MAP_TAPER) | AM_KIND_MAP_BIT(AM_MAP_BEND))) == 0u)
// Programs with no map and only convolution primitives: groups of points along a grid line
// can share their y and z terms (PointsL).
#define AM_LINES_OK                                                                                              \
  ((kAmFeatures & (AM_FEAT_OP_BIT(AM_OP_BEGINMAP) | AM_FEAT_OP_BIT(AM_OP_ENDMAP) | AM_FEAT_CLASS_BIT(AM_PRIM_SKELETAL) | \
                   AM_FEAT_CLASS_BIT(AM_PRIM_CAPSULE))) == 0u)
#define AM_LACKS_SKEL(k) ((kAmKinds & AM_KIND_SKEL_BIT(k)) == 0u)
#define AM_LACKS_COMBINE(m) ((kAmFeatures & AM_FEAT_COMBINE_BIT(m)) == 0u)

// C++ mirror: PolyParams in engine/gpu/polygonizer/gpu_polygonizer.cpp (std140).
layout(set = 0, binding = AM_PB_PARAMS, std430) readonly buffer PolyParams {
  vec4 gridOrigin;  // xyz: world position of grid corner (0,0,0); w: cell size h (m)
  uvec4 gridCells;  // xyz: cells per axis; w: workgroups a row of the fine passes' dispatch
  uvec4 gridBlocks; // xyz: blocks per axis; w: total blocks
  uvec4 progA;      // x: first op record (vec4 index), y: op count, z: first global primitive id, w: primitives
  uvec4 progB;      // the second program (morphs), else zero
  vec4 thresholds;  // x: T of A, y: T of B, z: culling margin on f, w: value forced on the grid boundary (< 0)
  uvec4 modes;      // x: AM_COMBINE_*, y: primitive-mask words per block, z: culling on, w: block capacity
  vec4 morph0;      // x: weight w, y: morph time t, z: time scale, w: a0
  vec4 morph1;      // x: a1, y: a2, z: a3, w: normal step (m)
  uvec4 caps;       // x: vertex capacity, y: triangle capacity, z: total primitives, w: 1 (kept opaque to the compiler: no unrolling)
  vec4 extra;       // x: reach dilation of a block box (m), w: the coherence tolerance factor (poly_cells_main.glsl)
  uvec4 superBlocks; // xyz: superblocks per axis; w: total
  uvec4 regions;    // x: 1 when the pool holds per-region op lists (gpu_region_op_lists.h), y: the superblocks'
                    // table (pool index, a uvec4 per superblock), z: their primitive masks (pool word index),
                    // w: log2 of the blocks a side of the regions whose lists the blocks walk (2: superblocks)
  uvec4 regionLists; // x: the blocks' regions' table, y, z: regions along x and y, w: the coherence frame stamp
  uvec4 colorPass;  // x: the colour table's pool index (poly_color_main.glsl; 0: no colour stream)
} P;

#if AM_POOL_STORAGE
layout(set = 0, binding = AM_PB_POOL_SSBO, std430) readonly buffer PoolStorage { uvec4 pool[]; };
#else
layout(set = 0, binding = AM_PB_POOL_UBO, std140) uniform PoolUniform { uvec4 pool[AM_POLY_UNIFORM_POOL_VEC4]; };
#endif
#define POOLF(i) uintBitsToFloat(pool[i])
#define POOLU(i) pool[i]

// The op lists the interpreters walk: x, y program A's first op record and op count, z, w B's. The
// whole programs, or with per-region lists (P.regions.x) those of one superblock: its programs
// specialised on the CPU to the primitives reaching it. Each pass selects them per block.
uvec4 gOps;
// The superblock's lists (its coarse pass).
void selectSuperblockOps(uint superblock) {
  gOps = P.regions.x != 0u ? POOLU(P.regions.y + superblock) : uvec4(P.progA.xy, P.progB.xy);
}
// The region (P.regions.w) holding block bc: 0 without region lists.
uint regionOf(uvec3 bc) {
  if (P.regions.x == 0u) return 0u;
  uvec3 rc = bc >> P.regions.w;
  return rc.x + P.regionLists.y * (rc.y + P.regionLists.z * rc.z);
}
// The lists of a block's region (its coarse and fine passes).
void selectRegionOps(uint region) {
  gOps = P.regions.x != 0u ? POOLU(P.regionLists.x + region) : uvec4(P.progA.xy, P.progB.xy);
}

layout(set = 0, binding = AM_PB_BOUNDS, std430) readonly buffer PrimBounds { vec4 primBounds[]; };
layout(set = 0, binding = AM_PB_BLOCK_MASK, std430) buffer BlockMask { uint blockMask[]; };
layout(set = 0, binding = AM_PB_BLOCK_SLOT, std430) buffer BlockSlot { uint blockSlot[]; };
layout(set = 0, binding = AM_PB_ACTIVE, std430) buffer ActiveBlocks { uint activeBlocks[]; };
layout(set = 0, binding = AM_PB_CONTROL, std430) buffer Control { uint control[]; };

// The fine passes (one workgroup per active block, dispatched in rows of P.gridCells.w
// workgroups): this workgroup's slot, and whether it is one of the active slots.
uint fineSlot() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }
// None once a pass has found its loops cut short (AM_OVERFLOW_LOOPS): the frame's data is not to be
// trusted, and the emit pass would otherwise index shared memory with stale edge prefixes.
uint fineSlots() {
  if ((control[AM_CTL_OVERFLOW] & AM_OVERFLOW_LOOPS) != 0u) return 0u;
  return min(control[AM_CTL_ACTIVE], P.modes.w);
}

// lavapipe (llvmpipe) ends every loop of a shader invocation once AM_POLY_LLVMPIPE_LOOP_LIMIT loop
// iterations have run in it, all loops counted together (gallivm's loop limiter): past that each
// loop runs its current iteration and stops, and the pass computes garbage from half-walked
// programs. A loop of two iterations at the end of a pass then runs once: the pass flags the frame
// (AM_OVERFLOW_LOOPS), which then draws nothing and is reported, never shown. (GpuPolygonizer
// refuses the programs that could get there beforehand: this catches what its bound missed.)
// pass: the pass's AM_OVERFLOW_CUT_* bit.
void flagCutLoops(uint pass) {
  uint n = 0u;
  for (uint k = 0u; k < 2u * P.caps.w; ++k) ++n;
  if (n < 2u) atomicOr(control[AM_CTL_OVERFLOW], AM_OVERFLOW_LOOPS | pass);
}

#define kInf uintBitsToFloat(0x7f800000u)

// Grid position of block b.
uvec3 blockCoord(uint b) {
  uvec3 nb = P.gridBlocks.xyz;
  return uvec3(b % nb.x, (b / nb.x) % nb.y, b / (nb.x * nb.y));
}

// activeBlocks[] holds each active block's grid position packed 10 bits per axis, so the
// fine passes need no integer division by the (run-time) block counts: on lavapipe a
// vector division by a non-constant is 8 scalar divisions, and LLVM repeated them at
// each use of the position.
uint packBlockCoord(uvec3 bc) { return bc.x | bc.y << 10 | bc.z << 20; }
uvec3 unpackBlockCoord(uint p) { return uvec3(p & 1023u, (p >> 10) & 1023u, p >> 20); }
uint blockIndex(uvec3 bc) { return bc.x + P.gridBlocks.x * (bc.y + P.gridBlocks.y * bc.z); }

// Cells of block bc along each axis (8, fewer at the far end of the grid).
uvec3 blockCells(uvec3 bc) { return min(uvec3(AM_POLY_BLOCK), P.gridCells.xyz - bc * uint(AM_POLY_BLOCK)); }

vec3 cornerPosition(uvec3 g) { return P.gridOrigin.xyz + P.gridOrigin.w * vec3(g); }

// Word w of the primitive bitmask at maskBase (a block's, or a superblock's). The normals pass
// defines it as the union of its vertices' blocks' masks (poly_normals_main.glsl).
#ifndef AM_BLOCK_MASK_WORD
#define AM_BLOCK_MASK_WORD(maskBase, word_) blockMask[(maskBase) + (word_)]
#endif

bool primActive(uint maskBase, uint g) { return ((AM_BLOCK_MASK_WORD(maskBase, g >> 5) >> (g & 31u)) & 1u) != 0u; }

// Whether any of the primitives first .. first + n - 1 reaches the block.
bool anyPrimActive(uint maskBase, uint first, uint n) {
  uint end = first + n, bits = 0u;
  for (uint g0 = first & ~31u; g0 < end; g0 += 32u) {
    uint w = AM_BLOCK_MASK_WORD(maskBase, g0 >> 5);
    if (g0 < first) w &= ~0u << (first - g0);
    if (end - g0 < 32u) w &= (1u << (end - g0)) - 1u;
    bits |= w;
  }
  return bits != 0u;
}

// Bit of the edge (base corner l, axis a) in its block's closed-box numbering.
uint edgeBit(uvec3 l, uint a) {
  if (a == 0u) return l.x + 8u * (l.y + 9u * l.z);
  if (a == 1u) return AM_POLY_EDGES_PER_AXIS + l.x + 9u * (l.y + 8u * l.z);
  return 2u * AM_POLY_EDGES_PER_AXIS + l.x + 9u * (l.y + 9u * l.z);
}

// Inverse of edgeBit: base corner and axis of closed-box edge e.
uvec3 edgeLocal(uint e, out uint a) {
  a = e / uint(AM_POLY_EDGES_PER_AXIS);
  uint r = e % uint(AM_POLY_EDGES_PER_AXIS);
  if (a == 0u) return uvec3(r % 8u, (r / 8u) % 9u, r / 72u);
  if (a == 1u) return uvec3(r % 9u, (r / 9u) % 8u, r / 72u);
  return uvec3(r % 9u, (r / 9u) % 9u, r / 81u);
}

uint cornerIndex(uvec3 l) { return (l.z * 9u + l.y) * 9u + l.x; }

// Marching-cubes case of cell x of a row of cells, from the sign masks (bit x: corner x is
// inside) of its four corner rows: (y, z), (y + 1, z), (y, z + 1), (y + 1, z + 1).
uint rowCellCase(uint r00, uint r10, uint r01, uint r11, uint x) {
  return ((r00 >> x) & 3u) | (((r10 >> x) & 3u) << 2) | (((r01 >> x) & 3u) << 4) | (((r11 >> x) & 3u) << 6);
}

// The active slot that makes the vertex of the edge at local base corner l
// (axis a) of block bc, and the edge's base corner local to that block. The
// owner is the block holding the base corner when it is active, else the
// first active block of the (up to 4) blocks sharing the edge, in a fixed
// order, so every block that uses the edge agrees. AM_POLY_NONE only when no
// block sharing it is active (never for an edge of an active block).
uint edgeOwner(uvec3 bc, uvec3 l, uint a, uint selfSlot, out uvec3 ownerLocal) {
  uint a1 = (a + 1u) % 3u, a2 = (a + 2u) % 3u;
  if (l[a1] < 8u && l[a2] < 8u) {
    ownerLocal = l;
    return selfSlot;
  }
  uvec3 g = bc * 8u + l;
  uvec3 base = g / 8u;
  uvec3 nb = P.gridBlocks.xyz;
  for (uint m = 0u; m < 4u; ++m) {
    uvec3 cand = base;
    if ((m & 1u) != 0u) {
      if (g[a1] % 8u != 0u || base[a1] == 0u) continue;
      cand[a1] -= 1u;
    }
    if ((m & 2u) != 0u) {
      if (g[a2] % 8u != 0u || base[a2] == 0u) continue;
      cand[a2] -= 1u;
    }
    if (any(greaterThanEqual(cand, nb))) continue;
    uint s = blockSlot[cand.x + nb.x * (cand.y + nb.y * cand.z)];
    if (s != AM_POLY_NONE) {
      ownerLocal = g - cand * 8u;
      return s;
    }
  }
  ownerLocal = l;
  return AM_POLY_NONE;
}
