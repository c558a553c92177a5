#version 450
#extension GL_GOOGLE_include_directive : require
// Ground grid line pixels (grid.vert): anti-aliased coverage across the line,
// faded out with distance from the camera and, for minor and major lines,
// before the radius where they would crowd together on screen.
#include "frame.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) noperspective in float inAcross;
layout(location = 2) flat in vec4 inStyle;
layout(location = 3) flat in vec2 inShape;
layout(location = 0) out vec4 outColor;

void main() {
  float coverage = clamp(inShape.x + 0.5 - abs(inAcross), 0.0, 1.0);
  float dist = length(inWorldPos - frame.cameraPos.xyz);
  float fade = 1.0 - smoothstep(frame.grid.y, frame.grid.z, dist);
  fade *= 1.0 - smoothstep(0.6 * inShape.y, inShape.y, dist);
  float alpha = inStyle.a * coverage * fade;
  if (alpha < 0.004) discard;
  outColor = vec4(inStyle.rgb, alpha);
}
