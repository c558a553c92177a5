#version 450
#extension GL_GOOGLE_include_directive : require
// Weight-map overlay: the painted weight as a heat colour (0 blue, 0.25 cyan,
// 0.5 green, 0.75 yellow, 1 red), lit by a headlight so the shape still reads.
#include "frame.glsl"

#include "mesh_push.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in float inPaintWeight;
layout(location = 0) out vec4 outColor;

vec3 heat(float w) {
  w = clamp(w, 0.0, 1.0);
  return clamp(vec3(4.0 * w - 2.0, w < 0.5 ? 4.0 * w : 4.0 - 4.0 * w, 2.0 - 4.0 * w), 0.0, 1.0);
}

void main() {
  vec3 v = normalize(frame.cameraPos.xyz - inWorldPos);
  vec3 n = inWorldNormal;
  float len = length(n);
  n = len > 1e-12 ? n / len : v;
  if (dot(n, v) < 0.0) n = -n;
  float head = max(dot(n, v), 0.0);
  vec3 base = pow(heat(inPaintWeight), vec3(2.2));
  vec3 lit = base * (0.35 + 0.65 * head);
  outColor = vec4(pow(lit, vec3(1.0 / 2.2)), 1.0);
}
