#version 450
#extension GL_GOOGLE_include_directive : require
// Active-block compaction after a multi-group block scan (poly_compact.glsl).
#include "poly_common.glsl"
#include "poly_compact.glsl"

layout(local_size_x = AM_POLY_WG_LINEAR) in;
layout(set = 0, binding = AM_PB_BLOCK_FLAG, std430) readonly buffer BlockFlag { uvec2 blockFlag[]; };
layout(set = 0, binding = AM_PB_BLOCK_PREFIX, std430) readonly buffer BlockPrefix { uvec2 blockPrefix[]; };

void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= P.gridBlocks.w) return;
  compactBlock(b, blockFlag[b].x != 0u, blockPrefix[b].x);
}
