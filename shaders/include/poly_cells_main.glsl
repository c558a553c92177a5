// Fine pass 1: one workgroup per active block. Evaluates the field at the
// block's 9^3 grid corners, applies the grid-boundary rule, classifies the 8^3
// cells (marching-cubes case) and marks the crossing edges this block makes
// vertices for (edgeOwner). Writes the corner values, the edge bitmask with
// its popcount prefixes, and the block's (vertex, triangle) counts for the scan.
//
// Work is split by corner rows along x, so the bookkeeping is bit arithmetic
// on registers: invocation t < 81 evaluates corners x = 0..7 of row
// (y, z) = (t % 9, t / 9), invocations 81..91 the x = 8 column. Each row's
// signs become a 9-bit mask; a row's cells and its x, y and z edges come from
// its mask and those of the rows at +y, +z and +y+z, and its edges are
// contiguous bits of the block's edge mask (edgeBit), so they are set with a
// few atomics. On lavapipe every shared or storage load is a loop over the 8
// SIMD lanes: per-cell and per-edge loads cost most of this pass before.
#include "poly_common.glsl"
#include "poly_field.glsl"
#include "poly_table.glsl"

#define AM_FIELD_V AM_POLY_CORNER_V
#include "poly_field_batch.glsl"

#if AM_POLY_CORNER_V != 2
#error "the row layout evaluates 8 corners per invocation"
#endif
#if AM_POLY_WG_CELLS < 92
#error "the row layout needs 81 row invocations and 11 for the x = 8 column"
#endif

layout(local_size_x = AM_POLY_WG_CELLS) in;

layout(set = 0, binding = AM_PB_CORNERS, std430) writeonly buffer Corners { float corners[]; };
layout(set = 0, binding = AM_PB_EDGES, std430) writeonly buffer Edges { uint edges[]; };
layout(set = 0, binding = AM_PB_COUNTS, std430) writeonly buffer Counts { uvec2 counts[]; };

const uint kRows = 81u;  // corner rows along x of a block: (y, z) in [0, 8]^2
const uint kEvaluators = kRows + (kRows + 7u) / 8u;  // row invocations, then those of the x = 8 column

shared float sColumn[kRows];  // the x = 8 corner of each row
shared uint sRow[kRows];      // bit x: corner (x, y, z) of the row is inside (f >= 0)
shared uint sMask[AM_POLY_EDGE_WORDS];
shared uint sTriangles;

// Corner value with the grid-boundary rule: the boundary counts as outside, so
// a surface cut by it is closed.
float boundaryRule(uvec3 g, float v) {
  if (any(equal(g, uvec3(0u))) || any(equal(g, P.gridCells.xyz))) v = min(v, P.thresholds.w);
  return v;
}

// ORs the n-bit run `bits` into the block's edge mask from bit `first` (n <= 9).
void setEdgeBits(uint first, uint bits) {
  uint word = first >> 5, shift = first & 31u;
  if (bits == 0u) return;
  atomicOr(sMask[word], bits << shift);
  if (shift > 23u) atomicOr(sMask[min(word + 1u, uint(AM_POLY_EDGE_WORDS) - 1u)], bits >> (32u - shift));
}

// The crossing edges of `cross` (bit i: the edge whose base corner is at x = i of row (y, z),
// along axis a) that are on the block's high faces (an index reaching 8 on another axis):
// kept only where this block adopts them (edgeOwner); the others are owned here.
uint ownedEdges(uvec3 bc, uint slot, uint cross, uint highBits, uint y, uint z, uint a) {
  uint owned = cross & ~highBits;
  uint maybe = cross & highBits;
  while (maybe != 0u) {
    uint x = uint(findLSB(maybe));
    maybe &= maybe - 1u;
    uvec3 ownerLocal;
    if (edgeOwner(bc, uvec3(x, y, z), a, slot, ownerLocal) == slot) owned |= 1u << x;
  }
  return owned;
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

  // Corners: a row's x = 0..7 (t < 81) or eight of the x = 8 column (t >= 81).
  bool rowInvocation = t < kRows;
  uint y = t % 9u, z = t / 9u;
  uint columnFirst = (t - kRows) * 8u;  // t >= 81: rows columnFirst .. + 7 (clamped)
  PointsV w;
#define AM_ROW_CORNER(j, c)                                                                         \
  {                                                                                                 \
    uint k_ = min(columnFirst + 4u * j + c, kRows - 1u);                                            \
    uvec3 l_ = rowInvocation ? uvec3(4u * j + c, y, z) : uvec3(8u, k_ % 9u, k_ / 9u);             \
    AM_SET_POINT(w, j, c, cornerPosition(c0 + l_))                                                  \
  }
#define AM_ROW_CORNERS(j) AM_ROW_CORNER(j, 0) AM_ROW_CORNER(j, 1) AM_ROW_CORNER(j, 2) AM_ROW_CORNER(j, 3)
  AM_EACH(AM_ROW_CORNERS)
  vec4 f[AM_FIELD_V];
  if (t < kEvaluators) fieldV(b * P.modes.y, w, f);
  uint signs = 0u;
  const uint base = slot * AM_POLY_BLOCK_CORNERS;
  if (rowInvocation) {
    for (uint x = 0u; x < 8u; ++x) {
      uvec3 l = uvec3(x, y, z);
      float v = boundaryRule(c0 + l, x < 4u ? f[0][x] : f[1][x - 4u]);
      corners[base + cornerIndex(l)] = v;
      if (v >= 0.0) signs |= 1u << x;
    }
  } else if (t < kEvaluators) {
    for (uint c = 0u; c < 8u; ++c) {
      uint k = columnFirst + c;
      if (k >= kRows) break;
      uvec3 l = uvec3(8u, k % 9u, k / 9u);
      float v = boundaryRule(c0 + l, c < 4u ? f[0][c] : f[1][c - 4u]);
      corners[base + cornerIndex(l)] = v;
      sColumn[k] = v;
    }
  }
  barrier();
  if (rowInvocation) {
    if (sColumn[t] >= 0.0) signs |= 1u << 8;
    sRow[t] = signs;
    edges[slot * AM_POLY_EDGE_INFO + AM_POLY_EDGE_ROWS + t] = signs;
  }
  barrier();

  uint tris = 0u;
  if (rowInvocation) {
    uint r00 = signs;
    uint r10 = sRow[min(t + 1u, kRows - 1u)];   // row (y + 1, z) when y < 8
    uint r01 = sRow[min(t + 9u, kRows - 1u)];   // row (y, z + 1) when z < 8
    uint r11 = sRow[min(t + 10u, kRows - 1u)];  // row (y + 1, z + 1)
    uint cellBits = (1u << cnt.x) - 1u;          // x < cnt.x: cells and x edges inside the grid
    uint cornerBits = (2u << cnt.x) - 1u;        // x <= cnt.x
    if (y < cnt.y && z < cnt.z) {
      for (uint x = 0u; x < 8u; ++x) {
        uint cubeCase = rowCellCase(r00, r10, r01, r11, x);
        if (((cellBits >> x) & 1u) != 0u) tris += mcTriangleCount(cubeCase);
      }
    }
    // Crossing edges along x (edgeBit: x + 8 (y + 9 z)), y (648 + x + 9 (y + 8 z)), z (1296 + x + 9 (y + 9 z)).
    // High faces: y or z = 8 for x edges; x = 8 or z = 8 for y edges; x = 8 or y = 8 for z edges.
    if (y <= cnt.y && z <= cnt.z) {
      uint cross = (r00 ^ (r00 >> 1)) & cellBits;
      uint high = (y == 8u || z == 8u) ? 0xffu : 0u;
      setEdgeBits(8u * (y + 9u * z), ownedEdges(bc, slot, cross, high, y, z, 0u));
    }
    if (y < cnt.y && z <= cnt.z) {
      uint cross = (r00 ^ r10) & cornerBits;
      uint high = z == 8u ? 0x1ffu : 0x100u;
      setEdgeBits(uint(AM_POLY_EDGES_PER_AXIS) + 9u * (y + 8u * z), ownedEdges(bc, slot, cross, high, y, z, 1u));
    }
    if (z < cnt.z && y <= cnt.y) {
      uint cross = (r00 ^ r01) & cornerBits;
      uint high = y == 8u ? 0x1ffu : 0x100u;
      setEdgeBits(2u * uint(AM_POLY_EDGES_PER_AXIS) + 9u * (y + 9u * z), ownedEdges(bc, slot, cross, high, y, z, 2u));
    }
  }
  if (tris > 0u) atomicAdd(sTriangles, tris);
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
