// Fine pass 2: one workgroup per active block, after the scan gave every
// block its first vertex and first triangle. Writes the block's vertices
// (one per owned crossing edge, interpolated like the CPU polygoniser; their
// normals come from the normals pass, poly_normals_main.glsl) and its
// triangles, whose corners are the vertices of their edges wherever those were
// made (edgeOwner), so vertices are shared and the mesh is watertight. Nothing
// is written past the capacities (the args pass has flagged the overflow).
//
// As in the cells pass, the bookkeeping avoids per-element loads (each one a
// loop over the SIMD lanes on lavapipe): the vertex list comes from the 64
// mask words (one invocation per word, a loop over its set bits), corner
// values are read only at the vertices' edges, and the cell cases of a row of
// 8 cells come from four corner-row sign masks written by the cells pass.
#include "poly_common.glsl"
#include "poly_table.glsl"

layout(local_size_x = AM_POLY_WG_EMIT) in;

layout(set = 0, binding = AM_PB_CORNERS, std430) readonly buffer Corners { float corners[]; };
layout(set = 0, binding = AM_PB_EDGES, std430) readonly buffer Edges { uint edges[]; };
layout(set = 0, binding = AM_PB_OFFSETS, std430) readonly buffer Offsets { uvec2 offsets[]; };
// One vec4 per vertex: on lavapipe each store is a loop over the SIMD lanes, so one vec4 store
// costs far less than three float stores. positions[].w carries the vertex's block primitive
// mask (its word offset) to the normals pass; the draw reads xyz.
layout(set = 0, binding = AM_PB_POSITIONS, std430) writeonly buffer Positions { vec4 positions[]; };
layout(set = 0, binding = AM_PB_NORMALS, std430) writeonly buffer Normals { vec4 normals[]; };
layout(set = 0, binding = AM_PB_INDICES, std430) writeonly buffer Indices { uint indices[]; };


// (AM_POLY_EMIT_SHARED_BYTES counts these: keep it in step.)
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

void main() {
  uint slot = fineSlot();
  if (slot >= fineSlots()) return;  // the last row's spare workgroups (the whole workgroup returns)
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
      sVertexEdge[min(p++, uint(AM_POLY_BLOCK_EDGES) - 1u)] = 32u * t + bit;  // in bounds whatever the prefixes
    }
  }
  barrier();
  uint vertices = sPrefix[AM_POLY_EDGE_WORDS - 1] + bitCount(sMask[AM_POLY_EDGE_WORDS - 1]);
  uint vertexBase = offsets[slot].x;
  const uint cornerBase = slot * AM_POLY_BLOCK_CORNERS;
  // The block's vertices, one per invocation in turn. The normals pass (poly_normals_main.glsl)
  // then takes the field's gradient at every vertex of the mesh, with no idle lanes per block;
  // it reads the block's primitive mask from w and keeps the edge direction written here where
  // the gradient vanishes.
  for (uint v = t; v < vertices; v += AM_POLY_WG_EMIT) {
    vec3 pos, dir;
    float f0;
    placeVertex(sVertexEdge[v], c0, cornerBase, pos, dir, f0);
    uint out_ = vertexBase + v;
    if (out_ < P.caps.x) {
      positions[out_] = vec4(pos, uintBitsToFloat(b * P.modes.y));
      normals[out_] = vec4(f0 >= 0.0 ? dir : -dir, 0.0);  // towards outside
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
