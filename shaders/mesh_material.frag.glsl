#version 450
#extension GL_GOOGLE_include_directive : require
// Viewport shading of a character's opaque meshes: the material's base colour
// (include/mesh_material.glsl) under the viewport lights (include/mesh_shading.glsl).
#include "frame.glsl"

#include "mesh_push.glsl"
#include "mesh_shading.glsl"
#include "mesh_material.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = amShadeMeshBase(inWorldPos, inWorldNormal, amMaterialBase());
}
