// Constants of the GPU polygoniser shared by engine/gpu/polygonizer/gpu_polygonizer.cpp,
// gpu_field_program.cpp and shaders/poly_*.comp.glsl (docs/gpu-polygonizer.md).
// Only preprocessor definitions, so GLSL and C++ read the same values.
#ifndef ANIMORPH_POLY_CONSTANTS_H
#define ANIMORPH_POLY_CONSTANTS_H

// Blocks of 8^3 cells: the unit of culling, of per-block primitive lists and of
// one workgroup in the fine passes.
#define AM_POLY_BLOCK 8
// Superblocks of 4^3 blocks (32^3 cells): the coarse pass first bounds the field
// per superblock, then only the blocks of superblocks that can hold surface do
// the per-block lists and intervals (the coarse pass was ~20% of a 256^3 frame).
#define AM_POLY_SUPER 4
#define AM_POLY_BLOCK_CORNERS 729  // (8 + 1)^3 grid corners of a block
#define AM_POLY_BLOCK_CELLS 512
// Edges of a block's closed box (base corner in [0,8] on the two other axes,
// [0,8) along the edge): 3 * 8 * 9 * 9. A block owns the ones whose base
// corner lies in it, and adopts face edges whose owner block is not active.
#define AM_POLY_BLOCK_EDGES 1944
#define AM_POLY_EDGES_PER_AXIS 648
#define AM_POLY_EDGE_WORDS 64  // bitmask words per block (>= 1944 / 32), then 64 prefix counts
#define AM_POLY_EDGE_ROWS 128  // then 81 corner-row sign masks (bit x: corner (x, y, z) inside; row y + 9 z)
#define AM_POLY_EDGE_INFO 256  // uints per block: 64 mask words + 64 exclusive popcount prefixes + rows

// Workgroup sizes (x only; multiples of 8 suit lavapipe's 8-wide SIMD).
#define AM_POLY_WG_BLOCKS 64   // coarse pass: one invocation per block
#define AM_POLY_WG_CELLS 104   // corners + cells pass: one workgroup per active block (95 evaluators, 8 sub-block intervals)
#define AM_POLY_WG_EMIT 64     // emit pass: one workgroup per active block (one invocation per mask word and per row)
#define AM_POLY_WG_NORMALS 64  // normals pass: four vertices per invocation, over all the mesh's vertices
// Points per invocation of the batched field evaluation, in vec4, 1 or 2 (shaders/include/poly_field_batch.glsl):
// a primitive's record is loaded once per invocation and applied to all its points (on lavapipe a
// load inside a loop costs far more than the arithmetic).
#define AM_POLY_CORNER_V 2     // corners: 8 per invocation (4, 16 and 32 measured no faster on lavapipe)
#define AM_POLY_NORMAL_V 2     // stencil normals: 2 vertices per evaluation, 4 points each (tetrahedral gradient)
#define AM_POLY_WG_SCAN 256
#define AM_POLY_SCAN_PER_GROUP 1024  // elements per scan workgroup (4 per invocation)
#define AM_POLY_SCAN_MAX_GROUPS 1024 // so at most 1M elements per scan
#define AM_POLY_SCAN_SINGLE_MAX 65536 // up to this many elements, one workgroup scans (poly_scan_single.comp)
#define AM_POLY_WG_LINEAR 64   // compaction and helpers
// Workgroups a row of the fine passes' indirect dispatch (one workgroup per active block): Vulkan's
// guaranteed maxComputeWorkGroupCount[0]. Beyond it the blocks continue in further rows (y), so a
// 512^3 grid (262 144 blocks) never dispatches more than a device may.
#define AM_POLY_MAX_DISPATCH_X 65535
// Shared memory of the largest workgroup, the emit pass (poly_emit_main.glsl: edge mask and
// prefixes, vertex list, triangle runs and list, a total), in bytes: 18 788. Vulkan guarantees
// 16 KiB (maxComputeSharedMemorySize) and 128 invocations a workgroup; desktop GPUs and lavapipe
// have 32 KiB or more and 1024, and a device short of either is reported (GpuPolygonizer::create).
#define AM_POLY_EMIT_SHARED_BYTES \
  (4 * (2 * AM_POLY_EDGE_WORDS + AM_POLY_BLOCK_EDGES + AM_POLY_WG_EMIT + 5 * AM_POLY_BLOCK_CELLS + 1))

// Interpreter limits: programs beyond them are reported and polygonised on the CPU.
#define AM_POLY_MAX_STACK 16
#define AM_POLY_MAX_MAP_DEPTH 16
// Operands of one hyper-blend are read from the stack, so at most the stack size.

// The primitive/op pool in a uniform buffer of this many vec4 (64 KiB) when it
// fits and the device allows it; else the storage-buffer variant of the shaders.
#define AM_POLY_UNIFORM_POOL_VEC4 4096

// Edge parameter kept in [snap, 1 - snap], as the CPU polygoniser does.
#define AM_POLY_SNAP 1e-3

// Op codes (values of animorph::OpCode).
#define AM_OP_PRIMS 0
#define AM_OP_CONST 1
#define AM_OP_SUM 2
#define AM_OP_MAX 3
#define AM_OP_MIN 4
#define AM_OP_HYPERBLEND 5
#define AM_OP_DIFFERENCE 6
#define AM_OP_RUNION 7
#define AM_OP_RINTERSECTION 8
#define AM_OP_BOUNDEDBLEND 9
#define AM_OP_BEGINMAP 10
#define AM_OP_ENDMAP 11
#define AM_OP_REMAP 15  // bit 15 of the features: free between the class and combine bits

// Primitive classes (animorph::PrimClass).
#define AM_PRIM_SKELETAL 0
#define AM_PRIM_CONVOLUTION 1
#define AM_PRIM_CAPSULE 2

// Skeleton kinds (animorph::SkeletonKind).
#define AM_SKEL_POINT 0
#define AM_SKEL_SPHERE 1
#define AM_SKEL_SEGMENT 2
#define AM_SKEL_CYLINDER 3
#define AM_SKEL_CONE 4
#define AM_SKEL_DISC 5
#define AM_SKEL_CIRCLE 6
#define AM_SKEL_TRIANGLE 7
#define AM_SKEL_CURVE 8

// Space map kinds (animorph::SpaceMapKind).
#define AM_MAP_AFFINE 0
#define AM_MAP_TWIST 1
#define AM_MAP_TAPER 2
#define AM_MAP_BEND 3

// Pipeline variants: the field shaders are specialised (constant_id 0 and 1)
// on what the programs use, so code for anything else is removed when the
// pipeline is created. On lavapipe an `if` is not a branch (both sides run
// under a lane mask), so an interpreter that tests every op code pays for
// every op's code at every op; specialised, it pays for its own only.
// Features (constant_id 0): op codes, primitive classes, how programs combine.
#define AM_FEAT_OP_BIT(c) (1u << (c))                 // bits 0..11 and 15: AM_OP_*
#define AM_FEAT_CLASS_BIT(k) (1u << (12 + (k)))       // bits 12..14: AM_PRIM_*
#define AM_FEAT_COMBINE_BIT(m) (1u << (16 + (m)))     // bits 16..18: AM_COMBINE_*
// Kinds (constant_id 1): skeleton kinds and space-map kinds.
#define AM_KIND_SKEL_BIT(k) (1u << (k))               // bits 0..8: AM_SKEL_*
#define AM_KIND_MAP_BIT(k) (1u << (16 + (k)))         // bits 16..19: AM_MAP_*
#define AM_FEAT_ALL 0xffffffffu                       // the generic variant

// Pool record sizes in vec4.
#define AM_REC_OP 2
#define AM_REC_CONV 3
#define AM_REC_SKEL 6  // (p0, kind|count<<8), (p1, r0), (p2, r1), (R, I, k, curve), (capsule a, reach), (capsule b, 0)
#define AM_REC_CAPSULE 2
#define AM_REC_MAP 4
#define AM_REC_BOUND 4  // storage buffer of bounds: (a, radius), (b, 0), (box min, 0), (box max, 0)

// How the two programs combine (GpuPolygonizer settings).
#define AM_COMBINE_SINGLE 0
#define AM_COMBINE_INTERPOLATE 1
#define AM_COMBINE_SPACETIME 2

// Descriptor bindings of the polygoniser's single descriptor set.
#define AM_PB_PARAMS 0       // uniform: PolyParams
#define AM_PB_POOL_UBO 1     // uniform: vec4 pool[AM_POLY_UNIFORM_POOL_VEC4]
#define AM_PB_POOL_SSBO 2    // storage: vec4 pool[]
#define AM_PB_BOUNDS 3       // storage: vec4 per primitive bound (AM_REC_BOUND each)
#define AM_PB_TABLE 4        // uniform: marching-cubes table
#define AM_PB_BLOCK_MASK 5   // storage: primitive bitmask per block, then per superblock
#define AM_PB_BLOCK_FLAG 6   // storage: uvec2 per block (active, 0): scan input
#define AM_PB_BLOCK_PREFIX 7 // storage: uvec2 per block: scan output
#define AM_PB_BLOCK_SLOT 8   // storage: uint per block: active slot or AM_POLY_NONE
#define AM_PB_ACTIVE 9       // storage: uint per active slot: block position (packBlockCoord)
#define AM_PB_CORNERS 10     // storage: float, AM_POLY_BLOCK_CORNERS per active slot
#define AM_PB_EDGES 11       // storage: uint, AM_POLY_EDGE_INFO per active slot
#define AM_PB_COUNTS 12      // storage: uvec2 per active slot (vertices, triangles): scan input
#define AM_PB_OFFSETS 13     // storage: uvec2 per active slot: scan output
#define AM_PB_PARTIALS 14    // storage: uvec2 per scan group
#define AM_PB_CONTROL 15     // storage: counters and indirect arguments (AM_CTL_*)
#define AM_PB_POSITIONS 16   // storage: float xyz per vertex (vertex buffer)
#define AM_PB_NORMALS 17     // storage: float xyz per vertex (vertex buffer)
#define AM_PB_INDICES 18     // storage: uint per triangle corner (index buffer)
#define AM_PB_SUPER_FLAG 19  // storage: uint per superblock: can hold surface (their primitive
                             // bitmasks follow the blocks' in AM_PB_BLOCK_MASK)
// Temporal coherence (GpuPolygonizeSettings::reuseToleranceCells), per block of the grid:
#define AM_PB_KEPT_CORNERS 20  // storage: uint (float bits; AM_POLY_NOT_KEPT: none) per corner, AM_POLY_BLOCK_CORNERS a block
#define AM_PB_KEPT_INFO 21     // storage: uvec4 (frame stamp, accumulated bound, smallest |f|, 0 -- floats as bits)
#define AM_PB_REUSE_BOUND 22   // storage: float: how far the field moved there since the previous frame
#define AM_PB_COUNT 23
#define AM_POLY_NOT_KEPT 0xffffffffu

#define AM_POLY_NONE 0xffffffffu

// Control buffer layout (uint indices).
#define AM_CTL_ACTIVE 0      // active blocks (may exceed the block capacity)
#define AM_CTL_VERTICES 1    // vertices of the mesh (may exceed the vertex capacity)
#define AM_CTL_TRIANGLES 2   // triangles (may exceed the triangle capacity)
#define AM_CTL_OVERFLOW 3    // AM_OVERFLOW_* bits: the mesh is incomplete, grow and redo
#define AM_CTL_DISPATCH 4    // VkDispatchIndirectCommand (x, y, z) for the fine passes
#define AM_CTL_DRAW 8        // VkDrawIndexedIndirectCommand (5 uints)
#define AM_CTL_SCAN_TOTAL 14 // uvec2 total of the last scan
#define AM_CTL_NORMALS 16     // VkDispatchIndirectCommand of the normals pass
#define AM_CTL_REUSED 19     // blocks whose corners were the kept ones (temporal coherence)
#define AM_CTL_UINTS 20
#define AM_CTL_READBACK_UINTS 20  // counters copied to the host after each frame

#define AM_OVERFLOW_BLOCKS 1u
#define AM_OVERFLOW_VERTICES 2u
#define AM_OVERFLOW_TRIANGLES 4u
// A field pass found its loops cut short by the device (lavapipe stops every loop of a shader
// invocation once AM_POLY_LLVMPIPE_LOOP_LIMIT iterations have run in it, all loops together):
// the frame draws nothing and is not redone (GpuPolygonizer reports it).
#define AM_OVERFLOW_LOOPS 8u
// With AM_OVERFLOW_LOOPS: which pass found its loops cut (the error names it).
#define AM_OVERFLOW_CUT_COARSE 16u
#define AM_OVERFLOW_CUT_CELLS 32u
#define AM_OVERFLOW_CUT_NORMALS 64u
#define AM_POLY_LLVMPIPE_LOOP_LIMIT 65535
// The colour pass (poly_color_main.glsl) found its loops cut: that frame's colours are not trusted.
#define AM_OVERFLOW_CUT_COLORS 128u
// The colour pass writes each vertex's surface colour into its normal's w: RGBA8 bits (linear r, g, b
// in the low bytes) with this tag in the top byte; w = 0 (no tag): no colour, the mesh's one tone.
#define AM_POLY_COLOR_TAG 62u

// Push constant x of the normals pass: the invocation's four vertices, or only vertex k (AM_NORMALS_VERTEX + k).
#define AM_NORMALS_ALL 0
#define AM_NORMALS_VERTEX 1

// Push constants (one uvec4) of the helper passes.
#define AM_SCAN_REDUCE 0
#define AM_SCAN_PARTIALS 1
#define AM_SCAN_DOWNSWEEP 2
#define AM_SCAN_SOURCE_BLOCKS 0  // block flags -> block prefix
#define AM_SCAN_SOURCE_COUNTS 1  // per-slot counts -> offsets
#define AM_COARSE_SUPERBLOCKS 0  // coarse pass: one invocation per superblock
#define AM_COARSE_BLOCKS 1       // coarse pass: one invocation per block
#define AM_ARGS_AFTER_BLOCKS 0
#define AM_ARGS_AFTER_COUNTS 1

#endif  // ANIMORPH_POLY_CONSTANTS_H
