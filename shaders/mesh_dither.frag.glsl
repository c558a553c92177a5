#version 450
#extension GL_GOOGLE_include_directive : require
// Cross-fade of a mesh and the implicit surface around markers B and C:
// order-independent screen-door transparency. A pixel is kept where the 4x4
// Bayer threshold lies below the opacity (pc.color.a), so no sorting is
// needed; AM_DRAW_DITHER_INVERT flips the threshold, so draws at opacities o
// and 1 - o cover complementary pixels. A separate shader so that opaque
// meshes keep early depth testing (no discard in mesh.frag).
#include "frame.glsl"
#include "transition_constants.h"

#include "mesh_push.glsl"
#include "mesh_shading.glsl"
#include "dither.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 0) out vec4 outColor;

void main() {
  if (amDitheredOut()) discard;
  outColor = vec4(amShadeMesh(inWorldPos, inWorldNormal).rgb, 1.0);
}
