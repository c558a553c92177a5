#version 450
#extension GL_GOOGLE_include_directive : require
// A skinned mesh collapsing onto / expanding from its stand-in
// (include/transition.glsl): mesh.vert's inputs plus the per-vertex stand-in
// binding, the per-draw transition parameters in set 1. Shares mesh.frag.
#include "frame.glsl"
#include "transition_constants.h"
// False: the draw's binding has no stand-in colours (the fragment stage does not read them).
layout(constant_id = AM_SPEC_STANDIN_COLOR) const bool amStandinColored = true;
#include "skinned_vertex.glsl"
layout(location = AM_VERTEX_STANDIN_OFFSET) in vec4 inStandinOffset;  // dp, m
layout(location = AM_VERTEX_STANDIN_NORMAL) in vec4 inStandinNormal;  // n~, stand-in colour (gpu_standin_binding.h)

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
  // The mesh's material (texture coordinates, COLOR_0) as it is, faded by the pixel into the
  // stand-in's colour where the vertex lands, with the position's alpha (the CPU's
  // transitionColors at the vertices). The colour is RGBA8 in the bits of n~'s w, its top byte
  // AM_STANDIN_COLOR_TAG (none: 0).
  amPassMaterial();
  const uint packed = floatBitsToUint(inStandinNormal.w);
  if (amStandinColored && (packed >> 24) == AM_STANDIN_COLOR_TAG)
    outStandinColor = vec4(unpackUnorm4x8(packed).rgb, clamp(amTransitionAlpha(inStandinOffset.w), 0.0, 1.0));
  gl_Position = frame.viewProj * wp;
  gl_Position.z -= pc.depthPull * gl_Position.w;
}
