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

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 0) out vec4 outColor;

const float kBayer4[16] = float[](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

void main() {
  ivec2 q = ivec2(gl_FragCoord.xy) & 3;
  float threshold = (kBayer4[q.y * 4 + q.x] + 0.5) / 16.0;
  if ((pc.flags & AM_DRAW_DITHER_INVERT) != 0u) threshold = 1.0 - threshold;
  if (!(pc.color.a > threshold)) discard;
  outColor = vec4(amShadeMesh(inWorldPos, inWorldNormal).rgb, 1.0);
}
