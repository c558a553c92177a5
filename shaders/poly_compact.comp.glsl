#version 450
#extension GL_GOOGLE_include_directive : require
// Active-block compaction after the block scan: active block b gets slot
// prefix[b] (block order, so the output is deterministic), the slot's block
// position is recorded (packBlockCoord), and blockSlot[] maps blocks to slots (AM_POLY_NONE: inactive, or
// beyond the block capacity, which the args pass reports as an overflow).
#include "poly_common.glsl"

layout(local_size_x = AM_POLY_WG_LINEAR) in;
layout(set = 0, binding = AM_PB_BLOCK_FLAG, std430) readonly buffer BlockFlag { uvec2 blockFlag[]; };
layout(set = 0, binding = AM_PB_BLOCK_PREFIX, std430) readonly buffer BlockPrefix { uvec2 blockPrefix[]; };

void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= P.gridBlocks.w) return;
  uint slot = AM_POLY_NONE;
  if (blockFlag[b].x != 0u) {
    uint s = blockPrefix[b].x;
    if (s < P.modes.w) {
      activeBlocks[s] = packBlockCoord(blockCoord(b));
      slot = s;
    }
  }
  blockSlot[b] = slot;
}
