#version 450
#extension GL_GOOGLE_include_directive : require
// A scan and everything that follows it in one workgroup, for arrays of at most
// AM_POLY_SCAN_SINGLE_MAX elements (a 256^3 grid has 32768 blocks). On lavapipe
// every dispatch costs ~0.1 ms of its own, so this one dispatch replaces five
// after the coarse pass (three scan phases, compaction, args) and four after
// the cells pass. Each invocation takes a contiguous run of the array: the
// workgroup-wide scan runs once, whatever the length.
//   pc.y = AM_SCAN_SOURCE_BLOCKS: block flags -> compaction (poly_compact.glsl) -> fine-pass dispatch
//   pc.y = AM_SCAN_SOURCE_COUNTS: per-slot counts of the active slots -> offsets -> draw and normals
//   pc.z: element count (the block count, or the block capacity)
#include "poly_common.glsl"
#include "poly_scan_group.glsl"
#include "poly_compact.glsl"
#include "poly_args.glsl"

layout(local_size_x = AM_POLY_WG_SCAN) in;
layout(push_constant) uniform ScanPush { uvec4 pc; };  // y: source, z: element count

layout(set = 0, binding = AM_PB_BLOCK_FLAG, std430) readonly buffer BlockFlag { uvec2 blockFlag[]; };
layout(set = 0, binding = AM_PB_COUNTS, std430) readonly buffer Counts { uvec2 counts[]; };
layout(set = 0, binding = AM_PB_OFFSETS, std430) writeonly buffer Offsets { uvec2 offsets[]; };

void main() {
  uint t = gl_LocalInvocationID.x;
  bool blocks = pc.y == AM_SCAN_SOURCE_BLOCKS;
  // Counts: only the slots the cells pass ran (the rest are zero).
  uint n = blocks ? pc.z : min(pc.z, fineSlots());
  uint per = (n + AM_POLY_WG_SCAN - 1u) / AM_POLY_WG_SCAN;
  uint first = min(t * per, n), last = min(first + per, n);
  uvec2 s = uvec2(0u);
  for (uint i = first; i < last; ++i) s += blocks ? blockFlag[i] : counts[i];
  uvec2 run = workgroupExclusive(s);
  uvec2 total = sums[AM_POLY_WG_SCAN - 1u];
  for (uint i = first; i < last; ++i) {
    uvec2 v = blocks ? blockFlag[i] : counts[i];
    if (blocks) compactBlock(i, v.x != 0u, run.x);
    else offsets[i] = run;
    run += v;
  }
  if (t == 0u) {
    if (blocks) argsAfterBlocks(total.x);
    else argsAfterCounts(total.x, total.y);
  }
}
