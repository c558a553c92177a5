#version 450
#extension GL_GOOGLE_include_directive : require
// Weight-map overlay: a skinned mesh (the same linear blend skinning as
// mesh.vert) with one painted weight per vertex as an extra vertex stream,
// handed to weight_overlay.frag for the heat colour.
#include "frame.glsl"
#include "skinned_vertex.glsl"
layout(location = AM_VERTEX_PAINT_WEIGHT) in float inPaintWeight;

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out float outPaintWeight;

void main() {
  vec3 p = inPosition, n = inNormal;
  amMorphVertex(uint(gl_VertexIndex), p, n);
  mat4 world = pc.model * amSkinMatrix(inJoints0, inWeights0, inJoints1, inWeights1);
  vec4 wp = world * vec4(p, 1.0);
  outWorldPos = wp.xyz;
  outWorldNormal = transpose(inverse(mat3(world))) * n;
  outPaintWeight = inPaintWeight;
  gl_Position = frame.viewProj * wp;
}
