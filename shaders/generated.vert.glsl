#version 450
#extension GL_GOOGLE_include_directive : require
// A non-skinned mesh generated on the GPU (GpuPolygonizer): world = model * p,
// normal by the inverse-transpose of model. Shares mesh.frag's push constants; drawn by
// generated.frag (generated_dither.frag when cross-faded, mesh.frag for the wireframe).
// The normal's w carries the vertex's surface colour from the colour pass (RGBA8 bits, linear,
// top byte AM_POLY_COLOR_TAG, poly_constants.h); w = 0: no colour, the draw's one tone.
#include "frame.glsl"
#include "poly_constants.h"

layout(location = AM_VERTEX_POSITION) in vec3 inPosition;
layout(location = AM_VERTEX_NORMAL) in vec4 inNormal;

#include "mesh_push.glsl"

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out vec4 outSurfaceColor;  // rgb linear; a: 1 with a colour, 0 without

void main() {
  vec4 wp = pc.model * vec4(inPosition, 1.0);
  outWorldPos = wp.xyz;
  outWorldNormal = transpose(inverse(mat3(pc.model))) * inNormal.xyz;
  const uint packed = floatBitsToUint(inNormal.w);
  outSurfaceColor = (packed >> 24) == AM_POLY_COLOR_TAG ? vec4(unpackUnorm4x8(packed).rgb, 1.0) : vec4(0.0);
  gl_Position = frame.viewProj * wp;
  gl_Position.z -= pc.depthPull * gl_Position.w;
}
