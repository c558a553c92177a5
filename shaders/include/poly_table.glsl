// The marching-cubes table of engine/core/poly/marching_cubes_table.cpp,
// uploaded once: per case two uvec4, the triangles' edges as 4-bit entries
// (words 0..4) and the triangle count (second.y); then the 12 edges as
// corner0 | corner1 << 4 | axis << 8, four per uvec4.
layout(set = 0, binding = AM_PB_TABLE, std430) readonly buffer MarchingCubes { uvec4 mcTable[]; };

uint mcTriangleCount(uint cubeCase) { return mcTable[2u * cubeCase + 1u].y; }

// Edge (0..11) of corner q (0..2) of triangle tri in case cubeCase.
uint mcEdge(uint cubeCase, uint tri, uint q) {
  uint n = 3u * tri + q;
  uint word = n >> 3;
  uint w = word < 4u ? mcTable[2u * cubeCase][word] : mcTable[2u * cubeCase + 1u].x;
  return (w >> ((n & 7u) * 4u)) & 15u;
}

uint mcEdgeInfo(uint e) { return mcTable[512u + (e >> 2)][e & 3u]; }
