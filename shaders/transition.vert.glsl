#version 450
#extension GL_GOOGLE_include_directive : require
// A skinned mesh collapsing onto / expanding from its stand-in
// (include/transition.glsl): mesh.vert's inputs plus the per-vertex stand-in
// binding, the per-draw transition parameters in set 1. Shares mesh.frag.
#include "frame.glsl"
#include "transition_constants.h"
#include "skinned_vertex.glsl"
layout(location = AM_VERTEX_STANDIN_OFFSET) in vec4 inStandinOffset;  // dp, m
layout(location = AM_VERTEX_STANDIN_NORMAL) in vec4 inStandinNormal;  // n~, 0

#include "transition.glsl"
#include "material_vertex.glsl"

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outWorldNormal;

void main() {
  vec4 wp;
  vec3 wn;
  // Blend shapes: the morphed vertex at alpha = 0; the binding's offset is from
  // the unmorphed one, so alpha = 1 still lands on the stand-in (morph/transition.cpp).
  vec3 p = inPosition, n = inNormal;
  amMorphVertex(uint(gl_VertexIndex), p, n);
  vec4 dpm = vec4(inStandinOffset.xyz - (p - inPosition), inStandinOffset.w);
  amTransitionVertex(p, n, inJoints0, inWeights0, inJoints1, inWeights1, dpm, inStandinNormal.xyz, wp, wn);
  outWorldPos = wp.xyz;
  outWorldNormal = wn;
  // The mesh's material (texture coordinates, COLOR_0) as it is: a transition that fades the
  // colour towards its stand-in's overwrites outColor0 here (the pixel then multiplies it).
  amPassMaterial();
  gl_Position = frame.viewProj * wp;
  gl_Position.z -= pc.depthPull * gl_Position.w;
}
