#version 450
#extension GL_GOOGLE_include_directive : require
// Polygoniser pass "normals" with the primitive pool in a storage buffer
// (the body is shaders/include/poly_normals_main.glsl; gpu_polygonizer.cpp picks the variant).
#define AM_POOL_STORAGE 1
#include "poly_normals_main.glsl"
