// Fine pass 2: one workgroup per active block, after the scan gave every
// block its first vertex and first triangle. Writes the block's vertices
// (one per owned crossing edge, interpolated like the CPU polygoniser, normal
// from the field gradient by a tetrahedral difference stencil, two vertices per
// invocation) and its triangles, whose
// corners are the vertices of their edges wherever those were made (edgeOwner),
// so vertices are shared and the mesh is watertight. Nothing is written past
// the capacities (the args pass has flagged the overflow).
#include "poly_common.glsl"
#include "poly_field.glsl"
#include "poly_table.glsl"

#define AM_FIELD_V AM_POLY_NORMAL_V
#include "poly_field_batch.glsl"

layout(local_size_x = AM_POLY_WG_CELLS) in;

layout(set = 0, binding = AM_PB_CORNERS, std430) readonly buffer Corners { float corners[]; };
layout(set = 0, binding = AM_PB_EDGES, std430) readonly buffer Edges { uint edges[]; };
layout(set = 0, binding = AM_PB_OFFSETS, std430) readonly buffer Offsets { uvec2 offsets[]; };
layout(set = 0, binding = AM_PB_POSITIONS, std430) writeonly buffer Positions { float positions[]; };
layout(set = 0, binding = AM_PB_NORMALS, std430) writeonly buffer Normals { float normals[]; };
layout(set = 0, binding = AM_PB_INDICES, std430) writeonly buffer Indices { uint indices[]; };

const uint kCellsPerInvocation = (AM_POLY_BLOCK_CELLS + AM_POLY_WG_CELLS - 1) / AM_POLY_WG_CELLS;

shared float sCorner[AM_POLY_BLOCK_CORNERS];
shared uint sMask[AM_POLY_EDGE_WORDS];
shared uint sPrefix[AM_POLY_EDGE_WORDS];
shared uint sVertexEdge[AM_POLY_BLOCK_EDGES];
shared uint sTriangleRun[AM_POLY_WG_CELLS];

uint cellCase(uvec3 l) {
  uint cubeCase = 0u;
  for (uint q = 0u; q < 8u; ++q)
    if (sCorner[cornerIndex(l + uvec3(q & 1u, (q >> 1) & 1u, q >> 2))] >= 0.0) cubeCase |= 1u << q;
  return cubeCase;
}

// Global index of the vertex of the edge (base corner l, axis a) of block bc.
uint vertexIndex(uvec3 bc, uvec3 l, uint a, uint slot) {
  uvec3 ownerLocal;
  uint owner = edgeOwner(bc, l, a, slot, ownerLocal);
  if (owner == AM_POLY_NONE) return 0u;  // unreachable for a crossing edge of an active block
  uint bit = edgeBit(ownerLocal, a);
  uint word = bit >> 5;
  uint info = owner * AM_POLY_EDGE_INFO;
  uint below = edges[info + word] & ((1u << (bit & 31u)) - 1u);
  return offsets[owner].x + edges[info + AM_POLY_EDGE_WORDS + word] + bitCount(below);
}

// Position of the vertex on closed-box edge e of the block at grid corner c0
// (t = f0 / (f0 - f1) kept in [snap, 1 - snap]); dir: the edge's direction, f0: its base value.
void placeVertex(uint e, uvec3 c0, out vec3 pos, out vec3 dir, out float f0) {
  uint a;
  uvec3 l = edgeLocal(e, a);
  uvec3 l1 = l;
  l1[a] += 1u;
  f0 = sCorner[cornerIndex(l)];
  float f1 = sCorner[cornerIndex(l1)];
  float s = clamp(f0 / (f0 - f1), float(AM_POLY_SNAP), 1.0 - float(AM_POLY_SNAP));
  vec3 p0 = cornerPosition(c0 + l), p1 = cornerPosition(c0 + l1);
  pos = p0 + s * (p1 - p0);
  dir = normalize(p1 - p0);
}

// Writes vertex out_ (unless past the capacity) with the normal -grad f / |grad f| from the
// stencil values f; where the gradient vanishes, along the edge towards outside.
void writeVertex(uint out_, vec3 pos, vec4 f, vec3 dir, float f0) {
  vec3 g = vec3(dot(f, vec4(1, -1, -1, 1)), dot(f, vec4(-1, -1, 1, 1)), dot(f, vec4(-1, 1, -1, 1)));
  float len = length(g);
  vec3 normal = len > 1e-30 && !isinf(len) && !isnan(len) ? -g / len : (f0 >= 0.0 ? dir : -dir);
  if (out_ >= P.caps.x) return;
  positions[3u * out_] = pos.x;
  positions[3u * out_ + 1u] = pos.y;
  positions[3u * out_ + 2u] = pos.z;
  normals[3u * out_] = normal.x;
  normals[3u * out_ + 1u] = normal.y;
  normals[3u * out_ + 2u] = normal.z;
}

void main() {
  uint slot = gl_WorkGroupID.x;
  uint t = gl_LocalInvocationID.x;
  uint b = activeBlocks[slot];
  uvec3 bc = blockCoord(b);
  uvec3 c0 = bc * uint(AM_POLY_BLOCK);
  uvec3 cnt = blockCells(bc);
  for (uint i = t; i < uint(AM_POLY_BLOCK_CORNERS); i += AM_POLY_WG_CELLS)
    sCorner[i] = corners[slot * AM_POLY_BLOCK_CORNERS + i];
  if (t < uint(AM_POLY_EDGE_WORDS)) {
    sMask[t] = edges[slot * AM_POLY_EDGE_INFO + t];
    sPrefix[t] = edges[slot * AM_POLY_EDGE_INFO + AM_POLY_EDGE_WORDS + t];
  }
  barrier();
  // Compact this block's vertices (edge order), so every invocation works on one.
  for (uint e = t; e < uint(AM_POLY_BLOCK_EDGES); e += AM_POLY_WG_CELLS) {
    uint word = e >> 5, bit = e & 31u;
    if (((sMask[word] >> bit) & 1u) != 0u) sVertexEdge[sPrefix[word] + bitCount(sMask[word] & ((1u << bit) - 1u))] = e;
  }
  barrier();
  uint vertices = sPrefix[AM_POLY_EDGE_WORDS - 1] + bitCount(sMask[AM_POLY_EDGE_WORDS - 1]);
  uint vertexBase = offsets[slot].x;
  const float d = P.morph1.w;
  // Gradient by the tetrahedral stencil (4 points, second-order like central
  // differences): offsets d (1,-1,-1), d (-1,-1,1), d (-1,1,-1), d (1,1,1).
  const vec3 k0 = vec3(1, -1, -1), k1 = vec3(-1, -1, 1), k2 = vec3(-1, 1, -1), k3 = vec3(1, 1, 1);
  uint pairs = (vertices + 1u) / 2u;
  for (uint pr = t; pr < pairs; pr += AM_POLY_WG_CELLS) {
    uint va = 2u * pr, vb = min(va + 1u, vertices - 1u);
    vec3 posA, dirA, posB, dirB;
    float fa, fb;
    placeVertex(sVertexEdge[va], c0, posA, dirA, fa);
    placeVertex(sVertexEdge[vb], c0, posB, dirB, fb);
    PointsV w;
    AM_SET_POINT(w, 0, 0, posA + d * k0) AM_SET_POINT(w, 0, 1, posA + d * k1)
    AM_SET_POINT(w, 0, 2, posA + d * k2) AM_SET_POINT(w, 0, 3, posA + d * k3)
    AM_SET_POINT(w, 1, 0, posB + d * k0) AM_SET_POINT(w, 1, 1, posB + d * k1)
    AM_SET_POINT(w, 1, 2, posB + d * k2) AM_SET_POINT(w, 1, 3, posB + d * k3)
    vec4 f[AM_FIELD_V];
    fieldV(b * P.modes.y, w, f);
    writeVertex(vertexBase + va, posA, f[0], dirA, fa);
    if (va + 1u < vertices) writeVertex(vertexBase + va + 1u, posB, f[1], dirB, fb);
  }
  // Triangles: a contiguous run of cells per invocation, in cell order.
  uint firstCell = t * kCellsPerInvocation;
  uint lastCell = min(firstCell + kCellsPerInvocation, uint(AM_POLY_BLOCK_CELLS));
  uint mine = 0u;
  for (uint c = firstCell; c < lastCell; ++c) {
    uvec3 l = uvec3(c & 7u, (c >> 3) & 7u, c >> 6);
    if (!any(greaterThanEqual(l, cnt))) mine += mcTriangleCount(cellCase(l));
  }
  sTriangleRun[t] = mine;
  barrier();
  if (t == 0u) {
    uint run = 0u;
    for (uint k = 0u; k < uint(AM_POLY_WG_CELLS); ++k) {
      uint c = sTriangleRun[k];
      sTriangleRun[k] = run;
      run += c;
    }
  }
  barrier();
  uint tri = offsets[slot].y + sTriangleRun[t];
  for (uint c = firstCell; c < lastCell; ++c) {
    uvec3 l = uvec3(c & 7u, (c >> 3) & 7u, c >> 6);
    if (any(greaterThanEqual(l, cnt))) continue;
    uint cubeCase = cellCase(l);
    uint nt = mcTriangleCount(cubeCase);
    for (uint k = 0u; k < nt; ++k, ++tri) {
      if (tri >= P.caps.y) continue;
      for (uint q = 0u; q < 3u; ++q) {
        uint info = mcEdgeInfo(mcEdge(cubeCase, k, q));
        uint corner = info & 15u, axis = info >> 8;
        uvec3 el = l + uvec3(corner & 1u, (corner >> 1) & 1u, corner >> 2);
        indices[3u * tri + q] = vertexIndex(bc, el, axis, slot);
      }
    }
  }
}
