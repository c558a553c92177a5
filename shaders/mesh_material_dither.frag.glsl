#version 450
#extension GL_GOOGLE_include_directive : require
// A character mesh cross-fading (screen-door transparency, include/dither.glsl)
// in its material's colours (include/mesh_material.glsl).
#include "frame.glsl"
#include "transition_constants.h"

#include "mesh_push.glsl"
#include "mesh_shading.glsl"
#include "mesh_material.glsl"
#include "dither.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 0) out vec4 outColor;

void main() {
  if (amDitheredOut()) discard;
  outColor = vec4(amShadeMeshBase(inWorldPos, inWorldNormal, amMaterialBase()).rgb, 1.0);
}
