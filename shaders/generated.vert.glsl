#version 450
#extension GL_GOOGLE_include_directive : require
// A non-skinned mesh generated on the GPU (GpuPolygonizer): world = model * p,
// normal by the inverse-transpose of model. Shares mesh.frag and its push constants.
#include "frame.glsl"

layout(location = AM_VERTEX_POSITION) in vec3 inPosition;
layout(location = AM_VERTEX_NORMAL) in vec3 inNormal;

#include "mesh_push.glsl"

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outWorldNormal;

void main() {
  vec4 wp = pc.model * vec4(inPosition, 1.0);
  outWorldPos = wp.xyz;
  outWorldNormal = transpose(inverse(mat3(pc.model))) * inNormal;
  gl_Position = frame.viewProj * wp;
  gl_Position.z -= pc.depthPull * gl_Position.w;
}
