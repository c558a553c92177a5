#version 450
#extension GL_GOOGLE_include_directive : require
// generated.frag's shading cross-faded by screen-door transparency (as mesh_dither.frag).
#include "frame.glsl"
#include "transition_constants.h"

#include "mesh_push.glsl"
#include "mesh_shading.glsl"
#include "dither.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec4 inSurfaceColor;
layout(location = 0) out vec4 outColor;

void main() {
  if (amDitheredOut()) discard;
  vec4 c = inSurfaceColor.a > 0.5 ? amShadeMeshBase(inWorldPos, inWorldNormal, inSurfaceColor.rgb)
                                  : amShadeMesh(inWorldPos, inWorldNormal);
  outColor = vec4(c.rgb, 1.0);
}
