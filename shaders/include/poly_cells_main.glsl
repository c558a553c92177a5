// Fine pass 1: one workgroup per active block. Evaluates the field at the
// block's 9^3 grid corners that can matter, applies the grid-boundary rule,
// classifies the 8^3 cells (marching-cubes case) and marks the crossing edges
// this block makes vertices for (edgeOwner). Writes the corner values, the
// edge bitmask with its popcount prefixes, the corner-row sign masks and the
// block's (vertex, triangle) counts for the scan.
//
// Sub-block culling (as the CPU polygoniser): the intervals of the block's
// eight 4^3-cell sub-blocks (the workgroup's last 8 invocations) leave out the corners only
// sub-blocks proved one-signed need. The corners left are listed in groups of
// up to 4 along a grid line (half rows x = 0..3 or 4..7 of a row (y, z); on the
// x = 8 face, y = 0..3, 4..7 or 8 of a column z) and each invocation evaluates
// two groups, so the work follows the list's length: on lavapipe only a loop's
// trip count skips work. For programs without maps whose primitives are all
// convolution segments, a group is evaluated as a line (PointsL): the kernel
// takes the terms of its two constant coordinates once per group.
//
// The bookkeeping is bit arithmetic on registers: each row's signs are a
// 9-bit mask; a row's cells and its x, y and z edges come from its mask and
// those of the rows at +y, +z and +y+z, and its edges are contiguous bits of
// the block's edge mask (edgeBit), so they are set with a few atomics. On
// lavapipe every shared or storage load is a loop over the 8 SIMD lanes:
// per-cell and per-edge loads cost most of this pass before.
#include "poly_common.glsl"
#include "poly_field.glsl"
#include "poly_table.glsl"

#define AM_FIELD_V AM_POLY_CORNER_V
#define AM_FIELD_LINES 1
#include "poly_field_batch.glsl"

#if AM_POLY_CORNER_V != 2
#error "the row layout evaluates 8 corners per invocation"
#endif
#if AM_POLY_WG_CELLS < 104
#error "the row layout needs 95 invocations (189 groups of corners, two per invocation), then 8 for the sub-blocks"
#endif

layout(local_size_x = AM_POLY_WG_CELLS) in;

layout(set = 0, binding = AM_PB_CORNERS, std430) writeonly buffer Corners { float corners[]; };
layout(set = 0, binding = AM_PB_EDGES, std430) writeonly buffer Edges { uint edges[]; };
layout(set = 0, binding = AM_PB_COUNTS, std430) writeonly buffer Counts { uvec2 counts[]; };
// Temporal coherence (GpuPolygonizeSettings::reuseToleranceCells; P.regionLists.w: this frame's
// stamp, 0: off): per block of the grid, its last corner values and their record.
layout(set = 0, binding = AM_PB_KEPT_CORNERS, std430) buffer KeptCorners { uint keptCorners[]; };
layout(set = 0, binding = AM_PB_KEPT_INFO, std430) buffer KeptInfo { uvec4 keptInfo[]; };
layout(set = 0, binding = AM_PB_REUSE_BOUND, std430) readonly buffer ReuseBound { float reuseBound[]; };

const uint kRows = 81u;                        // corner rows along x of a block: (y, z) in [0, 8]^2
const uint kHalfRows = 2u * kRows;             // groups of 4 corners: x = 0..3 or 4..7 of a row
const uint kFaceGroups = 27u;                  // the x = 8 face: y = 0..3, 4..7 and 8 of each column z
const uint kGroups = kHalfRows + kFaceGroups;
const uint kEvaluators = (kGroups + 1u) / 2u;  // two groups (8 corners) per invocation
// The sub-blocks' intervals: the workgroup's last 8 invocations (a SIMD group of their own on
// lavapipe, past the evaluators), so that no invocation walks both the interval program and the
// corners' program: lavapipe's loop limiter counts each SIMD group's iterations of all its loops.
const uint kSubBlockFirst = uint(AM_POLY_WG_CELLS) - 8u;

shared uint sSub;             // bit q: sub-block q may hold surface; bit 8 + q: proved inside
shared uint sGroup[kGroups];  // the groups to evaluate
shared uint sGroups;
shared uint sRow[kRows];      // bit x: corner (x, y, z) of the row is inside (f >= 0)
shared uint sMask[AM_POLY_EDGE_WORDS];
shared uint sTriangles;
shared uint sMinAbs;          // smallest |f| (as bits) over the corners stored off the grid boundary

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

// Sub-blocks: the 8 blocks of 4^3 cells of a block, q = qx + 2 qy + 4 qz; sub-block q spans
// corners [4 q, 4 q + 4] on each axis. Bit q of the result: sub-block q's corners include row (y, z).
uint rowSubBlocks(uint row) {
  uint y = row % 9u, z = row / 9u;
  uint ys = (y <= 4u ? 0x33u : 0u) | (y >= 4u ? 0xccu : 0u);  // qy = 0: q in {0, 1, 4, 5}
  uint zs = (z <= 4u ? 0x0fu : 0u) | (z >= 4u ? 0xf0u : 0u);  // qz = 0: q in {0, 1, 2, 3}
  return ys & zs;
}

// Sub-blocks whose corners include a corner of the box [lo, hi] (block-local corners).
uint cornerBoxSubBlocks(uvec3 lo, uvec3 hi) {
  uint xs = (lo.x <= 4u ? 0x55u : 0u) | (hi.x >= 4u ? 0xaau : 0u);  // qx = 0: q in {0, 2, 4, 6}
  uint ys = (lo.y <= 4u ? 0x33u : 0u) | (hi.y >= 4u ? 0xccu : 0u);
  uint zs = (lo.z <= 4u ? 0x0fu : 0u) | (hi.z >= 4u ? 0xf0u : 0u);
  return xs & ys & zs;
}

// Face group k (0..26) of the x = 8 face: column z = k / 3, y from 4 (k % 3); part 2 is the
// single corner y = 8.
uint faceGroupFirstY(uint k) { return 4u * (k % 3u); }
uint faceGroupCorners(uint k) { return k % 3u == 2u ? 1u : 4u; }
bool faceGroupLive(uint k, uint live) {
  uint y0 = faceGroupFirstY(k), z = k / 3u;
  return (cornerBoxSubBlocks(uvec3(8u, y0, z), uvec3(8u, y0 + faceGroupCorners(k) - 1u, z)) & live) != 0u;
}

// Corner c of group g, local to the block (c < 4; past the single corner of a face group's
// part 2 it lies outside the block and is evaluated but not stored).
uvec3 groupCorner(uint g, uint c) {
  if (g < kHalfRows) {
    uint row = g >> 1;
    return uvec3(4u * (g & 1u) + c, row % 9u, row / 9u);
  }
  uint k = g - kHalfRows;
  return uvec3(8u, faceGroupFirstY(k) + c, k / 3u);
}

// Stores the corner values f of group g (grid-boundary rule applied) and their sign bits; with
// temporal coherence (keep) also as the block's kept values (from kept). Returns the smallest |f|
// among them off the grid boundary.
float storeGroup(uint g, vec4 f, uvec3 c0, uint base, bool keep, uint kept) {
  uint n = g < kHalfRows ? 4u : faceGroupCorners(g - kHalfRows);
  uint bits = 0u;
  float minAbs = uintBitsToFloat(0x7f800000u);
  for (uint c = 0u; c < 4u; ++c) {
    uvec3 l = groupCorner(g, c);
    float v = boundaryRule(c0 + l, f[c]);
    if (c < n) corners[base + cornerIndex(l)] = v;
    if (c < n && keep) keptCorners[kept + cornerIndex(l)] = floatBitsToUint(v);
    uvec3 gc = c0 + l;
    if (c < n && !any(equal(gc, uvec3(0u))) && !any(equal(gc, P.gridCells.xyz))) minAbs = min(minAbs, abs(v));
    if (c < n && v >= 0.0) bits |= 1u << c;
  }
  if (g < kHalfRows) {
    if (bits != 0u) atomicOr(sRow[g >> 1], bits << (4u * (g & 1u)));
  } else {
    uint k = g - kHalfRows, row0 = faceGroupFirstY(k) + 9u * (k / 3u);
    for (uint c = 0u; c < 4u; ++c)
      if (((bits >> c) & 1u) != 0u) atomicOr(sRow[row0 + c], 1u << 8);
  }
  return minAbs;
}

// The kept values of group g's corners (kept: the block's first); false when one was not kept.
bool keptGroup(uint g, uint kept, out vec4 f) {
  uint n = g < kHalfRows ? 4u : faceGroupCorners(g - kHalfRows);
  bool all = true;
  f = vec4(0.0);
  for (uint c = 0u; c < 4u; ++c) {
    uint bits = c < n ? keptCorners[kept + cornerIndex(groupCorner(g, c))] : 0u;
    if (bits == AM_POLY_NOT_KEPT) all = false;
    f[c] = uintBitsToFloat(bits == AM_POLY_NOT_KEPT ? 0u : bits);
  }
  return all;
}

// Group g as a line of 4 points (PointsL): the varying coordinate, the two others, the axis.
void lineOfGroup(uint g, uvec3 c0, out vec4 v, out float s1, out float s2, out uint axis) {
  vec3 p0 = cornerPosition(c0 + groupCorner(g, 0u)), p1 = cornerPosition(c0 + groupCorner(g, 1u));
  vec3 p2 = cornerPosition(c0 + groupCorner(g, 2u)), p3 = cornerPosition(c0 + groupCorner(g, 3u));
  bool alongX = g < kHalfRows;
  v = alongX ? vec4(p0.x, p1.x, p2.x, p3.x) : vec4(p0.y, p1.y, p2.y, p3.y);
  s1 = alongX ? p0.y : p0.x;
  s2 = p0.z;
  axis = alongX ? 0u : 1u;
}

// Temporal coherence: whether block b's kept corners serve this frame (stamp; 0: nothing kept):
// they were valid through the previous frame and the field moved there (the bounds accumulated
// since they were made) by less than their smallest |f| times P.extra.w (the vertex rule:
// 2 tol / (1 + 2 tol); 0: exact reuse only). Otherwise the block is evaluated afresh and its
// corners marked not kept (invocation t's share) until stored. info, moved: the record, the bound.
bool keptServes(uint b, uint stamp, uint t, out uvec4 info, out float moved) {
  info = stamp != 0u ? keptInfo[b] : uvec4(0u);
  moved = stamp != 0u ? uintBitsToFloat(info.y) + reuseBound[b] : 0.0;
  bool reuse = stamp != 0u && info.x + 1u == stamp && (moved == 0.0 || moved <= P.extra.w * uintBitsToFloat(info.z));
  if (stamp != 0u && !reuse)
    for (uint i = t; i < uint(AM_POLY_BLOCK_CORNERS); i += uint(AM_POLY_WG_CELLS))
      keptCorners[b * uint(AM_POLY_BLOCK_CORNERS) + i] = AM_POLY_NOT_KEPT;
  return reuse;
}

// With reuse, the kept values of the invocation's groups into f; returns whether it must evaluate
// them all the same (not an evaluator, or a corner not kept: it then evaluates when an evaluator).
bool keptGroups(bool reuse, bool evaluator, uint gA, uint gB, bool hasB, uint kept, inout vec4 f[AM_FIELD_V]) {
  if (!reuse || !evaluator) return evaluator;
  bool keptA = keptGroup(gA, kept, f[0]);
  bool keptB = hasB ? keptGroup(gB, kept, f[1]) : true;
  return !(keptA && keptB);
}

// The block's edge mask with its popcount prefixes, its (vertex, triangle) counts, and with
// temporal coherence its kept corners' record and the reuse count.
void writeBlock(uint slot, uint t, uint b, uint stamp, bool reuse, float moved) {
  if (t < uint(AM_POLY_EDGE_WORDS)) edges[slot * AM_POLY_EDGE_INFO + t] = sMask[t];
  if (t != 0u) return;
  uint run = 0u;
  for (uint w = 0u; w < uint(AM_POLY_EDGE_WORDS); ++w) {
    edges[slot * AM_POLY_EDGE_INFO + AM_POLY_EDGE_WORDS + w] = run;
    run += bitCount(sMask[w]);
  }
  counts[slot] = uvec2(run, sTriangles);
  if (stamp != 0u) keptInfo[b] = uvec4(stamp, floatBitsToUint(reuse ? moved : 0.0), sMinAbs, 0u);
  if (reuse) atomicAdd(control[AM_CTL_REUSED], 1u);
}

void cellsPass() {
  uint slot = fineSlot();
  if (slot >= fineSlots()) return;  // the last row's spare workgroups (the whole workgroup returns)
  uint t = gl_LocalInvocationID.x;
  uvec3 bc = unpackBlockCoord(activeBlocks[slot]);
  uint b = blockIndex(bc);
  selectRegionOps(regionOf(bc));
  uvec3 c0 = bc * uint(AM_POLY_BLOCK);
  uvec3 cnt = blockCells(bc);
  if (t < uint(AM_POLY_EDGE_WORDS)) sMask[t] = 0u;
  if (t == 0u) sTriangles = 0u;

  const uint stamp = P.regionLists.w;
  const uint kept = b * uint(AM_POLY_BLOCK_CORNERS);
  uvec4 info;
  float moved;
  bool reuse = keptServes(b, stamp, t, info, moved);
  if (t == 0u) {
    sSub = 0u;
    sGroups = 0u;
    sMinAbs = reuse ? info.z : 0x7f800000u;
  }
  memoryBarrierBuffer();
  barrier();
  // Sub-block culling, as the CPU polygoniser: corners are evaluated only where a sub-block
  // whose interval does not prove one sign needs them. A sub-block proved one-signed holds
  // no surface, so its corners that are not evaluated take its sign (sub-blocks sharing a
  // corner agree: the true value there has both their signs) and its cells and edges stay
  // empty, as if evaluated.
  if (t >= kSubBlockFirst) {
    uint q = t - kSubBlockFirst;
    uvec3 h = 4u * uvec3(q & 1u, (q >> 1) & 1u, q >> 2);
    if (all(lessThan(h, cnt))) {
      int sign = P.modes.z == 0u ? 0 : boxSign(c0 + h, min(uvec3(4u), cnt - h), b * P.modes.y);
      if (sign >= 0) atomicOr(sSub, sign == 0 ? 1u << q : 256u << q);
    }
  }
  barrier();
  bool rowInvocation = t < kRows;
  uint y = t % 9u, z = t / 9u;
  uint live = sSub & 0xffu;
  if (rowInvocation) {
    uint near = rowSubBlocks(t);
    bool low = (near & live & 0x55u) != 0u;  // x = 0..3: sub-blocks qx = 0
    bool high = (near & live) != 0u;         // x = 4 (qx = 0 or 1), 5..7 (qx = 1)
    bool column = faceGroupLive(3u * z + min(y / 4u, 2u), live);  // the face group holding (8, y, z)
    uint inside = near & (sSub >> 8);
    uint defaults = ((inside & 0x55u) != 0u ? 0x1fu : 0u) | ((inside & 0xaau) != 0u ? 0x1f0u : 0u);
    sRow[t] = defaults & ~((low ? 0xfu : 0u) | (high ? 0xf0u : 0u) | (column ? 0x100u : 0u));
    if (low) sGroup[atomicAdd(sGroups, 1u)] = 2u * t;
    if (high) sGroup[atomicAdd(sGroups, 1u)] = 2u * t + 1u;
  }
  if (t < kFaceGroups && faceGroupLive(t, live)) sGroup[atomicAdd(sGroups, 1u)] = kHalfRows + t;
  barrier();

  // Corners: groups 2 t and 2 t + 1 of the list, 8 corners.
  uint groups = sGroups;
  bool evaluator = 2u * t < groups;
  uint gA = sGroup[min(2u * t, kGroups - 1u)];
  uint gB = sGroup[min(2u * t + 1u, kGroups - 1u)];
  vec4 f[AM_FIELD_V];
  const uint base = slot * AM_POLY_BLOCK_CORNERS;
  bool evaluate = keptGroups(reuse, evaluator, gA, gB, 2u * t + 1u < groups, kept, f);
  if (AM_LINES_OK) {
    PointsL wl;
#define AM_GROUP_LINE(j) lineOfGroup(j == 0 ? gA : gB, c0, wl.x[j], wl.y[j], wl.z[j], wl.axis[j]);
    AM_EACH(AM_GROUP_LINE)
    if (evaluate) fieldL(b * P.modes.y, wl, f);
  } else {
    PointsV w;
#define AM_GROUP_CORNER(j, c) AM_SET_POINT(w, j, c, cornerPosition(c0 + groupCorner(j == 0 ? gA : gB, c)))
#define AM_GROUP_CORNERS(j) AM_GROUP_CORNER(j, 0) AM_GROUP_CORNER(j, 1) AM_GROUP_CORNER(j, 2) AM_GROUP_CORNER(j, 3)
    AM_EACH(AM_GROUP_CORNERS)
    if (evaluate) fieldV(b * P.modes.y, w, f);
  }
  if (evaluator) {
    float minAbs = min(storeGroup(gA, f[0], c0, base, stamp != 0u, kept),
                       2u * t + 1u < groups ? storeGroup(gB, f[1], c0, base, stamp != 0u, kept) : 1e30);
    if (stamp != 0u) atomicMin(sMinAbs, floatBitsToUint(minAbs));
  }
  barrier();
  uint signs = rowInvocation ? sRow[t] : 0u;
  if (rowInvocation) edges[slot * AM_POLY_EDGE_INFO + AM_POLY_EDGE_ROWS + t] = signs;

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
  writeBlock(slot, t, b, stamp, reuse, moved);
}

void main() {
  cellsPass();
  flagCutLoops(AM_OVERFLOW_CUT_CELLS);
}
