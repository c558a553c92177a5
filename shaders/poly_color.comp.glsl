#version 450
#extension GL_GOOGLE_include_directive : require
// Polygoniser pass "colour" with the primitive pool in a uniform buffer
// (the body is shaders/include/poly_color_main.glsl; gpu_polygonizer.cpp picks the variant).
#define AM_POOL_STORAGE 0
#include "poly_color_main.glsl"
