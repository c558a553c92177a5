#version 450
#extension GL_GOOGLE_include_directive : require
// Viewport shading of opaque meshes (include/mesh_shading.glsl).
#include "frame.glsl"

#include "mesh_push.glsl"
#include "mesh_shading.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = amShadeMesh(inWorldPos, inWorldNormal);
}
