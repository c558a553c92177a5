#version 450
#extension GL_GOOGLE_include_directive : require
// Skinned mesh: linear blend skinning with up to 8 influences per vertex, as
// glTF defines it and engine/core/rig/skinning.cpp computes it on the CPU:
// skin = sum_k w_k * joint[j_k] (joints beyond the draw's joint count ignored),
// position = model * skin * p, normal = inverse-transpose of (model * skin) * n,
// with p and n the blend shapes' result (include/morph_targets.glsl).
#include "frame.glsl"
#include "skinned_vertex.glsl"
#include "material_vertex.glsl"

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outWorldNormal;

void main() {
  vec3 p = inPosition, n = inNormal;
  amMorphVertex(uint(gl_VertexIndex), p, n);
  mat4 world = pc.model * amSkinMatrix(inJoints0, inWeights0, inJoints1, inWeights1);
  vec4 wp = world * vec4(p, 1.0);
  outWorldPos = wp.xyz;
  outWorldNormal = transpose(inverse(mat3(world))) * n;
  amPassMaterial();
  gl_Position = frame.viewProj * wp;
  // Wireframe pass: pull towards the camera so lines win the depth test against their own faces.
  gl_Position.z -= pc.depthPull * gl_Position.w;
}
