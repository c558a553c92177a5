#version 450
#extension GL_GOOGLE_include_directive : require
// Weight-map overlay: a skinned mesh (the same linear blend skinning as
// mesh.vert) with one painted weight per vertex as an extra vertex stream,
// handed to weight_overlay.frag for the heat colour.
#include "frame.glsl"

layout(location = AM_VERTEX_POSITION) in vec3 inPosition;
layout(location = AM_VERTEX_NORMAL) in vec3 inNormal;
layout(location = AM_VERTEX_JOINTS0) in uvec4 inJoints0;
layout(location = AM_VERTEX_JOINTS1) in uvec4 inJoints1;
layout(location = AM_VERTEX_WEIGHTS0) in vec4 inWeights0;
layout(location = AM_VERTEX_WEIGHTS1) in vec4 inWeights1;
layout(location = AM_VERTEX_PAINT_WEIGHT) in float inPaintWeight;

layout(set = 0, binding = AM_BINDING_JOINTS, std430) readonly buffer Joints {
  mat4 joints[];
};

#include "mesh_push.glsl"
#include "skinning.glsl"

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out float outPaintWeight;

void main() {
  mat4 world = pc.model * amSkinMatrix(inJoints0, inWeights0, inJoints1, inWeights1);
  vec4 wp = world * vec4(inPosition, 1.0);
  outWorldPos = wp.xyz;
  outWorldNormal = transpose(inverse(mat3(world))) * inNormal;
  outPaintWeight = inPaintWeight;
  gl_Position = frame.viewProj * wp;
}
