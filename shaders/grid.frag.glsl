#version 450
#extension GL_GOOGLE_include_directive : require
// Anti-aliased grid lines (one pixel wide at any distance, from screen-space
// derivatives), a major line every 10 cells, the X axis red and the Z axis
// blue, fading out with distance from the camera.
#include "frame.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 0) out vec4 outColor;

float lineCoverage(vec2 coord, float widthPx) {
  vec2 d = fwidth(coord);
  vec2 g = abs(fract(coord - 0.5) - 0.5) / max(d, vec2(1e-6));
  return 1.0 - clamp(min(g.x, g.y) - 0.5 * (widthPx - 1.0), 0.0, 1.0);
}

void main() {
  vec2 coord = inWorldPos.xz / frame.grid.x;
  float minor = lineCoverage(coord, 1.0);
  float major = lineCoverage(coord / 10.0, 1.5);
  vec3 color = vec3(0.45);
  float alpha = max(minor * 0.35, major * 0.6);
  // Axes: the line z = 0 is the X axis, x = 0 the Z axis.
  vec2 axisD = fwidth(inWorldPos.xz);
  float xAxis = 1.0 - clamp(abs(inWorldPos.z) / max(axisD.y, 1e-6) - 0.5, 0.0, 1.0);
  float zAxis = 1.0 - clamp(abs(inWorldPos.x) / max(axisD.x, 1e-6) - 0.5, 0.0, 1.0);
  if (xAxis > 0.0) { color = mix(color, vec3(0.85, 0.25, 0.25), xAxis); alpha = max(alpha, 0.8 * xAxis); }
  if (zAxis > 0.0) { color = mix(color, vec3(0.25, 0.4, 0.9), zAxis); alpha = max(alpha, 0.8 * zAxis); }
  float dist = length(inWorldPos - frame.cameraPos.xyz);
  alpha *= 1.0 - smoothstep(frame.grid.y, frame.grid.z, dist);
  if (alpha < 0.004) discard;
  outColor = vec4(color, alpha);
}
