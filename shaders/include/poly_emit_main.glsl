// Fine pass 2: one workgroup per active block, after the scan gave every
// block its first vertex and first triangle. Writes the block's vertices
// (one per owned crossing edge, interpolated like the CPU polygoniser, normal
// from the field gradient: analytic as the CPU's, four vertices per invocation
// (poly_field_gradient.glsl), or for HyperBlend and non-affine maps by a
// tetrahedral difference stencil, two vertices per invocation) and its triangles, whose
// corners are the vertices of their edges wherever those were made (edgeOwner),
// so vertices are shared and the mesh is watertight. Nothing is written past
// the capacities (the args pass has flagged the overflow).
//
// As in the cells pass, the bookkeeping avoids per-element loads (each one a
// loop over the SIMD lanes on lavapipe): the vertex list comes from the 64
// mask words (one invocation per word, a loop over its set bits), corner
// values are read only at the vertices' edges, and the cell cases of a row of
// 8 cells come from four corner-row sign masks written by the cells pass.
#include "poly_common.glsl"
#include "poly_field.glsl"
#include "poly_table.glsl"

#define AM_FIELD_V AM_POLY_NORMAL_V
#include "poly_field_batch.glsl"
#include "poly_field_gradient.glsl"

layout(local_size_x = AM_POLY_WG_EMIT) in;

layout(set = 0, binding = AM_PB_CORNERS, std430) readonly buffer Corners { float corners[]; };
layout(set = 0, binding = AM_PB_EDGES, std430) readonly buffer Edges { uint edges[]; };
layout(set = 0, binding = AM_PB_OFFSETS, std430) readonly buffer Offsets { uvec2 offsets[]; };
// One vec4 per vertex (w unused): on lavapipe each store is a loop over the SIMD lanes, so
// one vec4 store costs far less than three float stores.
layout(set = 0, binding = AM_PB_POSITIONS, std430) writeonly buffer Positions { vec4 positions[]; };
layout(set = 0, binding = AM_PB_NORMALS, std430) writeonly buffer Normals { vec4 normals[]; };
layout(set = 0, binding = AM_PB_INDICES, std430) writeonly buffer Indices { uint indices[]; };


shared uint sMask[AM_POLY_EDGE_WORDS];
shared uint sPrefix[AM_POLY_EDGE_WORDS];
shared uint sVertexEdge[AM_POLY_BLOCK_EDGES];
shared uint sTriangleRun[AM_POLY_WG_EMIT];
shared uint sTriangle[AM_POLY_BLOCK_CELLS * 5];  // cell | its 3 edges << 9 (mcTriangleBits), in cell order
shared uint sTriangleTotal;

// Global index of the vertex of the edge (base corner l, axis a) of block bc.
uint vertexIndex(uvec3 bc, uvec3 l, uint a, uint slot, uint vertexBase) {
  uvec3 ownerLocal;
  uint owner = edgeOwner(bc, l, a, slot, ownerLocal);
  if (owner == AM_POLY_NONE) return 0u;  // unreachable for a crossing edge of an active block
  uint bit = edgeBit(ownerLocal, a);
  uint word = bit >> 5;
  uint below = (1u << (bit & 31u)) - 1u;
  if (owner == slot) return vertexBase + sPrefix[word] + bitCount(sMask[word] & below);
  uint info = owner * AM_POLY_EDGE_INFO;
  return offsets[owner].x + edges[info + AM_POLY_EDGE_WORDS + word] + bitCount(edges[info + word] & below);
}

// Position of the vertex on closed-box edge e of the block at grid corner c0
// (t = f0 / (f0 - f1) kept in [snap, 1 - snap]); dir: the edge's direction, f0: its base value.
void placeVertex(uint e, uvec3 c0, uint cornerBase, out vec3 pos, out vec3 dir, out float f0) {
  uint a;
  uvec3 l = edgeLocal(e, a);
  uvec3 l1 = l;
  l1[a] += 1u;
  f0 = corners[cornerBase + cornerIndex(l)];
  float f1 = corners[cornerBase + cornerIndex(l1)];
  float s = clamp(f0 / (f0 - f1), float(AM_POLY_SNAP), 1.0 - float(AM_POLY_SNAP));
  vec3 p0 = cornerPosition(c0 + l), p1 = cornerPosition(c0 + l1);
  pos = p0 + s * (p1 - p0);
  dir = normalize(p1 - p0);
}

// Writes vertex out_ (unless past the capacity) with the normal -g / |g| for the field
// gradient g; where the gradient vanishes, along the edge towards outside (outwardNormal).
void writeVertex(uint out_, vec3 pos, vec3 g, vec3 dir, float f0) {
  float len = length(g);
  vec3 normal = len > 1e-20 && !isinf(len) && !isnan(len) ? -g / len : (f0 >= 0.0 ? dir : -dir);
  if (out_ >= P.caps.x) return;
  positions[out_] = vec4(pos, 1.0);
  normals[out_] = vec4(normal, 0.0);
}

// Gradient from the tetrahedral stencil values f at offsets d k0..k3 (see main).
vec3 stencilGradient(vec4 f) {
  return vec3(dot(f, vec4(1, -1, -1, 1)), dot(f, vec4(-1, -1, 1, 1)), dot(f, vec4(-1, 1, -1, 1)));
}

void main() {
  uint slot = gl_WorkGroupID.x;
  uint t = gl_LocalInvocationID.x;
  uvec3 bc = unpackBlockCoord(activeBlocks[slot]);
  uint b = blockIndex(bc);
  uvec3 c0 = bc * uint(AM_POLY_BLOCK);
  uvec3 cnt = blockCells(bc);
  const uint info = slot * AM_POLY_EDGE_INFO;
  // This block's vertices in edge order: invocation t lists the set bits of mask word t.
  if (t < uint(AM_POLY_EDGE_WORDS)) {
    uint m = edges[info + t], p = edges[info + AM_POLY_EDGE_WORDS + t];
    sMask[t] = m;
    sPrefix[t] = p;
    while (m != 0u) {
      uint bit = uint(findLSB(m));
      m &= m - 1u;
      sVertexEdge[p++] = 32u * t + bit;
    }
  }
  barrier();
  uint vertices = sPrefix[AM_POLY_EDGE_WORDS - 1] + bitCount(sMask[AM_POLY_EDGE_WORDS - 1]);
  uint vertexBase = offsets[slot].x;
  const uint cornerBase = slot * AM_POLY_BLOCK_CORNERS;
  if (AM_ANALYTIC_GRADIENT) {
    // Four vertices per invocation, each with the analytic gradient at its position.
    uint quads = (vertices + 3u) / 4u;
    for (uint qd = t; qd < quads; qd += AM_POLY_WG_EMIT) {
      vec3 pos[4], dir[4];
      float f0[4];
      vec4 px, py, pz;
      for (uint c = 0u; c < 4u; ++c) {
        placeVertex(sVertexEdge[min(4u * qd + c, max(vertices, 1u) - 1u)], c0, cornerBase, pos[c], dir[c], f0[c]);
        px[c] = pos[c].x;
        py[c] = pos[c].y;
        pz[c] = pos[c].z;
      }
      Grad4 g = fieldGrad(b * P.modes.y, px, py, pz);
      for (uint c = 0u; c < 4u; ++c)
        if (4u * qd + c < vertices) writeVertex(vertexBase + 4u * qd + c, pos[c], vec3(g.x[c], g.y[c], g.z[c]), dir[c], f0[c]);
    }
  } else {
    const float d = P.morph1.w;
    // Gradient by the tetrahedral stencil (4 points, second-order like central
    // differences): offsets d (1,-1,-1), d (-1,-1,1), d (-1,1,-1), d (1,1,1).
    const vec3 k0 = vec3(1, -1, -1), k1 = vec3(-1, -1, 1), k2 = vec3(-1, 1, -1), k3 = vec3(1, 1, 1);
    uint pairs = (vertices + 1u) / 2u;
    for (uint pr = t; pr < pairs; pr += AM_POLY_WG_EMIT) {
      uint va = 2u * pr, vb = min(va + 1u, vertices - 1u);
      vec3 posA, dirA, posB, dirB;
      float fa, fb;
      placeVertex(sVertexEdge[va], c0, cornerBase, posA, dirA, fa);
      placeVertex(sVertexEdge[vb], c0, cornerBase, posB, dirB, fb);
      PointsV w;
      AM_SET_POINT(w, 0, 0, posA + d * k0) AM_SET_POINT(w, 0, 1, posA + d * k1)
      AM_SET_POINT(w, 0, 2, posA + d * k2) AM_SET_POINT(w, 0, 3, posA + d * k3)
      AM_SET_POINT(w, 1, 0, posB + d * k0) AM_SET_POINT(w, 1, 1, posB + d * k1)
      AM_SET_POINT(w, 1, 2, posB + d * k2) AM_SET_POINT(w, 1, 3, posB + d * k3)
      vec4 f[AM_FIELD_V];
      fieldV(b * P.modes.y, w, f);
      writeVertex(vertexBase + va, posA, stencilGradient(f[0]), dirA, fa);
      if (va + 1u < vertices) writeVertex(vertexBase + va + 1u, posB, stencilGradient(f[1]), dirB, fb);
    }
  }
  // Triangles: invocation t < 64 lists those of the 8 cells of row (y, z) = (t % 8, t / 8) in cell
  // order (x + 8 (y + 8 z)), cases from the corner-row sign masks; then each invocation writes whole
  // triangles from the list, so the per-corner work runs once per triangle, not once per cell and
  // triangle slot of every lane.
  uint y = t & 7u, z = t >> 3;
  bool rowInvocation = t < 64u && y < cnt.y && z < cnt.z;
  uint row = y + 9u * z;
  uint rows = info + AM_POLY_EDGE_ROWS;
  uint r00 = 0u, r10 = 0u, r01 = 0u, r11 = 0u;
  uint mine = 0u;
  if (rowInvocation) {
    r00 = edges[rows + row];
    r10 = edges[rows + row + 1u];
    r01 = edges[rows + row + 9u];
    r11 = edges[rows + row + 10u];
    for (uint x = 0u; x < cnt.x; ++x)
      mine += mcTriangleCount(rowCellCase(r00, r10, r01, r11, x));
  }
  sTriangleRun[t] = mine;
  barrier();
  if (t == 0u) {
    uint run = 0u;
    for (uint k = 0u; k < 64u; ++k) {
      uint c = sTriangleRun[k];
      sTriangleRun[k] = run;
      run += c;
    }
    sTriangleTotal = run;
  }
  barrier();
  if (rowInvocation && mine > 0u) {
    uint at = sTriangleRun[t];
    for (uint x = 0u; x < cnt.x; ++x) {
      uvec4 entry = mcTable[rowCellCase(r00, r10, r01, r11, x)];
      uint cell = x + 8u * (y + 8u * z);
      for (uint k = 0u; k < entry.w; ++k) sTriangle[at++] = cell | mcTriangleBits(entry, k) << 9;
    }
  }
  barrier();
  uint total = sTriangleTotal;
  uint firstTriangle = offsets[slot].y;
  for (uint i = t; i < total; i += AM_POLY_WG_EMIT) {
    uint entry = sTriangle[i];
    uint cell = entry & 511u;
    uint tri = firstTriangle + i;
    if (tri >= P.caps.y) continue;
    uvec3 l = uvec3(cell & 7u, (cell >> 3) & 7u, cell >> 6);
    for (uint q = 0u; q < 3u; ++q) {
      uint edge = (entry >> (9u + 5u * q)) & 31u;  // base corner | axis << 3
      uint corner = edge & 7u, axis = edge >> 3;
      uvec3 el = l + uvec3(corner & 1u, (corner >> 1) & 1u, corner >> 2);
      indices[3u * tri + q] = vertexIndex(bc, el, axis, slot, vertexBase);
    }
  }
}
