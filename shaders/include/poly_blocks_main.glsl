// Coarse pass, two levels (pc.x). AM_COARSE_SUPERBLOCKS: one invocation per
// superblock of 4^3 blocks lists the primitives whose bound reaches it and marks
// it when the field's interval over it does not prove one sign. AM_COARSE_BLOCKS:
// one invocation per block; a block of an unmarked superblock is culled at once
// (the superblock's proof covers it); otherwise it lists, among its superblock's
// primitives, those whose bound reaches the block (a bitmask over global
// primitive ids, the GPU form of FieldProgram::primitivesReaching + specialise)
// and is active unless its own interval proves one sign (FieldProgram::interval),
// with the CPU polygoniser's margin and grid-boundary rule at both levels.
// Culling off: every block active with every primitive. A superblock's
// primitive mask follows the blocks' masks in blockMask (superblock s at
// (blocks + s) * words), so the interval evaluator reads it like a block's.
#include "poly_common.glsl"
#include "poly_field.glsl"

layout(local_size_x = AM_POLY_WG_BLOCKS) in;
layout(push_constant) uniform CoarsePush { uvec4 pc; };  // x: AM_COARSE_*

layout(set = 0, binding = AM_PB_BLOCK_FLAG, std430) writeonly buffer BlockFlag { uvec2 blockFlag[]; };
layout(set = 0, binding = AM_PB_SUPER_FLAG, std430) buffer SuperFlag { uint superFlag[]; };

// Whether primitive g's bound reaches the box [dlo, dhi] (already grown by the normal step).
bool reaches(uint g, vec3 dlo, vec3 dhi) {
  vec4 bmin = primBounds[g * AM_REC_BOUND + 2u], bmax = primBounds[g * AM_REC_BOUND + 3u];
  if (any(greaterThan(bmin.xyz, dhi)) || any(lessThan(bmax.xyz, dlo))) return false;
  vec4 ba = primBounds[g * AM_REC_BOUND], bb = primBounds[g * AM_REC_BOUND + 1u];
  vec3 dc = 0.5 * (dlo + dhi);
  return length(dc - closestOnSegment(dc, ba.xyz, bb.xyz)) <= ba.w + 0.5 * length(dhi - dlo);
}

void coarsePass() {
  uint words = P.modes.y;
  uint total = P.caps.z;
  vec3 grow = vec3(P.extra.x);  // the normal pass may leave a box by the normal step
  if (pc.x == AM_COARSE_SUPERBLOCKS) {
    uint s = gl_GlobalInvocationID.x;
    if (s >= P.superBlocks.w) return;
    uvec3 ns = P.superBlocks.xyz;
    uvec3 sc = uvec3(s % ns.x, (s / ns.x) % ns.y, s / (ns.x * ns.y));
    uvec3 c0 = sc * uint(AM_POLY_SUPER * AM_POLY_BLOCK);
    uvec3 cnt = min(uvec3(AM_POLY_SUPER * AM_POLY_BLOCK), P.gridCells.xyz - c0);
    vec3 dlo = cornerPosition(c0) - grow, dhi = cornerPosition(c0 + cnt) + grow;
    uint maskBase = (P.gridBlocks.w + s) * words;
    if (P.regions.x != 0u) {
      // Per-region lists: the CPU listed the superblock's primitives with its op lists (the same
      // test on the same grown box); a loop over every primitive would outrun lavapipe's loop limit.
      for (uint w = 0u; w < words; ++w) {
        uint q = P.regions.z + s * words + w;
        blockMask[maskBase + w] = pool[q >> 2][q & 3u];
      }
    } else {
      for (uint w = 0u; w < words; ++w) {
        uint bits = 0u;
        for (uint k = 0u; k < 32u; ++k) {
          uint g = w * 32u + k;
          if (g >= total) break;
          if (reaches(g, dlo, dhi)) bits |= 1u << k;
        }
        blockMask[maskBase + w] = bits;
      }
    }
    selectSuperblockOps(s);
    // AM_POLY_NONE: the superblock's list is too long to walk here (gpu_polygonizer.cpp); its
    // blocks test themselves (its op count is 0, so the walk below costs nothing).
    bool untested = gOps.x == AM_POLY_NONE;
    superFlag[s] = untested || canHoldSurface(c0, cnt, maskBase) ? 1u : 0u;
    return;
  }
  uint b = gl_GlobalInvocationID.x;
  if (b >= P.gridBlocks.w) return;
  uint maskBase = b * words;
  if (P.modes.z == 0u) {
    for (uint w = 0u; w < words; ++w) blockMask[maskBase + w] = 0xffffffffu;
    blockFlag[b] = uvec2(1u, 0u);
    return;
  }
  uvec3 bc = blockCoord(b);
  uvec3 sc = bc / uint(AM_POLY_SUPER);
  uint s = sc.x + P.superBlocks.x * (sc.y + P.superBlocks.y * sc.z);
  if (superFlag[s] == 0u) {
    blockFlag[b] = uvec2(0u, 0u);
    return;
  }
  uvec3 c0 = bc * uint(AM_POLY_BLOCK);
  uvec3 cnt = blockCells(bc);
  selectRegionOps(regionOf(bc));
  vec3 dlo = cornerPosition(c0) - grow, dhi = cornerPosition(c0 + cnt) + grow;
  for (uint w = 0u; w < words; ++w) {
    uint candidates = blockMask[(P.gridBlocks.w + s) * words + w], bits = 0u;
    while (candidates != 0u) {
      uint k = uint(findLSB(candidates));
      candidates &= candidates - 1u;
      if (reaches(w * 32u + k, dlo, dhi)) bits |= 1u << k;
    }
    blockMask[maskBase + w] = bits;
  }
  blockFlag[b] = uvec2(canHoldSurface(c0, cnt, maskBase) ? 1u : 0u, 0u);
}

void main() {
  coarsePass();
  flagCutLoops(AM_OVERFLOW_CUT_COARSE);
}
