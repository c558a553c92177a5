#version 450
#extension GL_GOOGLE_include_directive : require
// Exclusive prefix sum of uvec2 arrays in three dispatches (no CPU read-back):
//   AM_SCAN_REDUCE:    group g sums its AM_POLY_SCAN_PER_GROUP elements into partials[g]
//   AM_SCAN_PARTIALS:  one group scans partials[] in place; the total goes to control[AM_CTL_SCAN_TOTAL]
//   AM_SCAN_DOWNSWEEP: group g writes the exclusive prefix of its elements plus partials[g]
// pc.y picks the arrays: block flags -> block prefix, or per-slot counts -> offsets.
#include "poly_common.glsl"
#include "poly_scan_group.glsl"

layout(local_size_x = AM_POLY_WG_SCAN) in;
layout(push_constant) uniform ScanPush { uvec4 pc; };  // x: phase, y: source, z: element count

layout(set = 0, binding = AM_PB_BLOCK_FLAG, std430) readonly buffer BlockFlag { uvec2 blockFlag[]; };
layout(set = 0, binding = AM_PB_BLOCK_PREFIX, std430) writeonly buffer BlockPrefix { uvec2 blockPrefix[]; };
layout(set = 0, binding = AM_PB_COUNTS, std430) readonly buffer Counts { uvec2 counts[]; };
layout(set = 0, binding = AM_PB_OFFSETS, std430) writeonly buffer Offsets { uvec2 offsets[]; };
layout(set = 0, binding = AM_PB_PARTIALS, std430) buffer Partials { uvec2 partials[]; };

uvec2 readIn(uint i) {
  if (i >= pc.z) return uvec2(0u);
  return pc.y == AM_SCAN_SOURCE_BLOCKS ? blockFlag[i] : counts[i];
}

void writeOut(uint i, uvec2 v) {
  if (i >= pc.z) return;
  if (pc.y == AM_SCAN_SOURCE_BLOCKS) blockPrefix[i] = v;
  else offsets[i] = v;
}

void main() {
  const uint per = AM_POLY_SCAN_PER_GROUP / AM_POLY_WG_SCAN;
  uint t = gl_LocalInvocationID.x;
  uint g = gl_WorkGroupID.x;
  if (pc.x == AM_SCAN_REDUCE) {
    uvec2 s = uvec2(0u);
    for (uint k = 0u; k < per; ++k) s += readIn(g * AM_POLY_SCAN_PER_GROUP + t * per + k);
    uvec2 prefix = workgroupExclusive(s);
    if (t == AM_POLY_WG_SCAN - 1u) partials[g] = prefix + s;
  } else if (pc.x == AM_SCAN_PARTIALS) {
    uint groups = (pc.z + AM_POLY_SCAN_PER_GROUP - 1u) / AM_POLY_SCAN_PER_GROUP;
    uvec2 v[per];
    uvec2 s = uvec2(0u);
    for (uint k = 0u; k < per; ++k) {
      uint i = t * per + k;
      v[k] = i < groups ? partials[i] : uvec2(0u);
      s += v[k];
    }
    uvec2 run = workgroupExclusive(s);
    for (uint k = 0u; k < per; ++k) {
      uint i = t * per + k;
      if (i < groups) partials[i] = run;
      run += v[k];
    }
    if (t == AM_POLY_WG_SCAN - 1u) {
      control[AM_CTL_SCAN_TOTAL] = run.x;
      control[AM_CTL_SCAN_TOTAL + 1] = run.y;
    }
  } else {
    uvec2 v[per];
    uvec2 s = uvec2(0u);
    uint first = g * AM_POLY_SCAN_PER_GROUP + t * per;
    for (uint k = 0u; k < per; ++k) {
      v[k] = readIn(first + k);
      s += v[k];
    }
    uvec2 run = workgroupExclusive(s) + partials[g];
    for (uint k = 0u; k < per; ++k) {
      writeOut(first + k, run);
      run += v[k];
    }
  }
}
