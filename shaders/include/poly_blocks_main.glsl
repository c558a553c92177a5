// Coarse pass: one invocation per block. Lists the primitives whose bound
// reaches the block (a bitmask over global primitive ids, the GPU form of
// FieldProgram::primitivesReaching + specialise) and marks the block active
// unless the field's interval over it proves one sign (FieldProgram::interval),
// with the CPU polygoniser's margin and grid-boundary rule. Culling off: every
// block active with every primitive.
#include "poly_common.glsl"
#include "poly_field.glsl"

layout(local_size_x = AM_POLY_WG_BLOCKS) in;

layout(set = 0, binding = AM_PB_BLOCK_FLAG, std430) writeonly buffer BlockFlag { uvec2 blockFlag[]; };

void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= P.gridBlocks.w) return;
  uint words = P.modes.y;
  uint maskBase = b * words;
  uint total = P.caps.z;
  if (P.modes.z == 0u) {
    for (uint w = 0u; w < words; ++w) blockMask[maskBase + w] = 0xffffffffu;
    blockFlag[b] = uvec2(1u, 0u);
    return;
  }
  uvec3 bc = blockCoord(b);
  uvec3 c0 = bc * uint(AM_POLY_BLOCK);
  uvec3 cnt = blockCells(bc);
  vec3 lo = cornerPosition(c0), hi = cornerPosition(c0 + cnt);
  // The reach test uses the box grown by the normal step, so the normal pass may leave the block a little.
  vec3 dlo = lo - vec3(P.extra.x), dhi = hi + vec3(P.extra.x);
  vec3 dc = 0.5 * (dlo + dhi);
  float dhalf = 0.5 * length(dhi - dlo);
  for (uint w = 0u; w < words; ++w) {
    uint bits = 0u;
    for (uint k = 0u; k < 32u; ++k) {
      uint g = w * 32u + k;
      if (g >= total) break;
      vec4 ba = primBounds[g * AM_REC_BOUND], bb = primBounds[g * AM_REC_BOUND + 1u];
      vec4 bmin = primBounds[g * AM_REC_BOUND + 2u], bmax = primBounds[g * AM_REC_BOUND + 3u];
      if (any(greaterThan(bmin.xyz, dhi)) || any(lessThan(bmax.xyz, dlo))) continue;
      if (length(dc - closestOnSegment(dc, ba.xyz, bb.xyz)) > ba.w + dhalf) continue;
      bits |= 1u << k;
    }
    blockMask[maskBase + w] = bits;
  }
  bool boundary = any(equal(c0, uvec3(0u))) || any(greaterThanEqual(c0 + cnt, P.gridCells.xyz));
  vec2 iv = combinedInterval(0.5 * (lo + hi), 0.5 * length(hi - lo), maskBase);
  float margin = P.thresholds.z;
  bool oneSigned = iv.y < -margin || (iv.x > margin && !boundary);
  blockFlag[b] = uvec2(oneSigned ? 0u : 1u, 0u);
}
