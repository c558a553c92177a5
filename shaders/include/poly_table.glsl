// The marching-cubes table of engine/core/poly/marching_cubes_table.cpp,
// uploaded once, one uvec4 per case with every edge already resolved to its
// base corner and axis (gpu_polygonizer.cpp), so writing a triangle needs no
// further table load (on lavapipe every load is a loop over the SIMD lanes):
// x, y, z: triangles 0-1, 2-3 and 4, 15 bits each (corner q of the triangle at
// bits 5 q: base corner 0..7 | axis << 3); w: the triangle count. The solid noise's permutation
// follows the 256 cases in the same buffer (poly_noise.comp.glsl).
layout(set = 0, binding = AM_PB_TABLE, std430) readonly buffer MarchingCubes { uvec4 mcTable[]; };

uint mcTriangleCount(uint cubeCase) { return mcTable[cubeCase].w; }

// The 15 bits of triangle k of a case whose table entry is c.
uint mcTriangleBits(uvec4 c, uint k) { return (c[k >> 1] >> (15u * (k & 1u))) & 0x7fffu; }
