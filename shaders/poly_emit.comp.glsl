#version 450
#extension GL_GOOGLE_include_directive : require
// Polygoniser pass "emit" with the primitive pool in a uniform buffer
// (the body is shaders/include/poly_emit_main.glsl; gpu_polygonizer.cpp picks the variant).
#define AM_POOL_STORAGE 0
#include "poly_emit_main.glsl"
