// Fine pass 1: one workgroup per active block. Evaluates the field at the
// block's 9^3 grid corners (4 AM_POLY_CORNER_V per invocation),
// applies the grid-boundary rule, classifies the 8^3 cells (marching-cubes case)
// and marks the crossing edges this block makes vertices for (edgeOwner).
// Writes the corner values, the edge bitmask with its popcount prefixes, and
// the block's (vertex, triangle) counts for the scan.
#include "poly_common.glsl"
#include "poly_field.glsl"
#include "poly_table.glsl"

#define AM_FIELD_V AM_POLY_CORNER_V
#include "poly_field_batch.glsl"

layout(local_size_x = AM_POLY_WG_CELLS) in;

layout(set = 0, binding = AM_PB_CORNERS, std430) writeonly buffer Corners { float corners[]; };
layout(set = 0, binding = AM_PB_EDGES, std430) writeonly buffer Edges { uint edges[]; };
layout(set = 0, binding = AM_PB_COUNTS, std430) writeonly buffer Counts { uvec2 counts[]; };

shared float sCorner[AM_POLY_BLOCK_CORNERS];
shared uint sMask[AM_POLY_EDGE_WORDS];
shared uint sTriangles;

uvec3 cornerLocal(uint idx) { return uvec3(idx % 9u, (idx / 9u) % 9u, idx / 81u); }

// Stores the values of corners idx .. idx + 3 (those of the block), with the
// grid-boundary rule: the boundary counts as outside, so a surface cut by it is closed.
void storeCorner(uint slot, uvec3 c0, uint idx, vec4 f) {
  for (uint c = 0u; c < 4u; ++c) {
    uint i = idx + c;
    if (i >= uint(AM_POLY_BLOCK_CORNERS)) break;
    uvec3 g = c0 + cornerLocal(i);
    float v = f[c];
    if (any(equal(g, uvec3(0u))) || any(equal(g, P.gridCells.xyz))) v = min(v, P.thresholds.w);
    sCorner[i] = v;
    corners[slot * AM_POLY_BLOCK_CORNERS + i] = v;
  }
}

void main() {
  uint slot = gl_WorkGroupID.x;
  uint t = gl_LocalInvocationID.x;
  uint b = activeBlocks[slot];
  uvec3 bc = blockCoord(b);
  uvec3 c0 = bc * uint(AM_POLY_BLOCK);
  uvec3 cnt = blockCells(bc);
  if (t < uint(AM_POLY_EDGE_WORDS)) sMask[t] = 0u;
  if (t == 0u) sTriangles = 0u;
  const uint kPoints = 4u * uint(AM_POLY_CORNER_V);
  for (uint first = t * kPoints; first < uint(AM_POLY_BLOCK_CORNERS); first += kPoints * AM_POLY_WG_CELLS) {
    PointsV w;
#define AM_CORNER_AT(j, c) AM_SET_POINT(w, j, c, cornerPosition(c0 + cornerLocal(min(first + 4u * j + c, uint(AM_POLY_BLOCK_CORNERS) - 1u))))
#define AM_CORNERS_AT(j) AM_CORNER_AT(j, 0) AM_CORNER_AT(j, 1) AM_CORNER_AT(j, 2) AM_CORNER_AT(j, 3)
    AM_EACH(AM_CORNERS_AT)
    vec4 f[AM_FIELD_V];
    fieldV(b * P.modes.y, w, f);
#define AM_CORNER_STORE(j) storeCorner(slot, c0, first + 4u * j, f[j]);
    AM_EACH(AM_CORNER_STORE)
  }
  barrier();
  uint tris = 0u;
  for (uint c = t; c < uint(AM_POLY_BLOCK_CELLS); c += AM_POLY_WG_CELLS) {
    uvec3 l = uvec3(c & 7u, (c >> 3) & 7u, c >> 6);
    if (any(greaterThanEqual(l, cnt))) continue;
    uint cubeCase = 0u;
    for (uint q = 0u; q < 8u; ++q)
      if (sCorner[cornerIndex(l + uvec3(q & 1u, (q >> 1) & 1u, q >> 2))] >= 0.0) cubeCase |= 1u << q;
    tris += mcTriangleCount(cubeCase);
  }
  if (tris > 0u) atomicAdd(sTriangles, tris);
  for (uint e = t; e < uint(AM_POLY_BLOCK_EDGES); e += AM_POLY_WG_CELLS) {
    uint a;
    uvec3 l = edgeLocal(e, a);
    uvec3 l1 = l;
    l1[a] += 1u;
    if (any(greaterThan(l1, cnt))) continue;  // beyond the grid
    bool in0 = sCorner[cornerIndex(l)] >= 0.0, in1 = sCorner[cornerIndex(l1)] >= 0.0;
    if (in0 == in1) continue;
    uvec3 ownerLocal;
    if (edgeOwner(bc, l, a, slot, ownerLocal) == slot) atomicOr(sMask[e >> 5], 1u << (e & 31u));
  }
  barrier();
  if (t < uint(AM_POLY_EDGE_WORDS)) edges[slot * AM_POLY_EDGE_INFO + t] = sMask[t];
  if (t == 0u) {
    uint run = 0u;
    for (uint w = 0u; w < uint(AM_POLY_EDGE_WORDS); ++w) {
      edges[slot * AM_POLY_EDGE_INFO + AM_POLY_EDGE_WORDS + w] = run;
      run += bitCount(sMask[w]);
    }
    counts[slot] = uvec2(run, sTriangles);
  }
}
