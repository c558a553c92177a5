#version 450
#extension GL_GOOGLE_include_directive : require
// Anti-aliased grid lines (about one pixel wide at any distance, from screen-space
// derivatives), a major line every 10 cells, the X axis red and the Z axis
// blue, fading out with distance from the camera. Pixels past the fade are
// discarded first: on CPU renderers the grid covers much of the screen.
#include "frame.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 0) out vec4 outColor;

// Coverage of a line at the integer coordinates, g = distance in pixels.
float coverage(vec2 g, float widthPx) {
  return 1.0 - clamp(min(g.x, g.y) - 0.5 * (widthPx - 1.0), 0.0, 1.0);
}

void main() {
  vec2 coord = inWorldPos.xz / frame.grid.x;          // in cells
  vec2 perPixel = max(fwidth(coord), vec2(1e-6));     // cells per pixel (before any discard)
  float fade = 1.0 - smoothstep(frame.grid.y, frame.grid.z, length(inWorldPos - frame.cameraPos.xyz));
  if (fade <= 0.0) discard;
  // Pixels between the lines go first too: every line (minor, major, axis) lies on a minor line,
  // and none covers a pixel more than 1.5 px from it (minor < 1, major < 1.25, axis < 1.5). On
  // llvmpipe a discard ends the work of a group of pixels that all took it, and most of the grid
  // is empty.
  vec2 g = abs(fract(coord - 0.5) - 0.5) / perPixel;  // pixels to the nearest minor line, per axis
  if (min(g.x, g.y) >= 1.5) discard;
  float minor = coverage(g, 1.0);
  float major = coverage(abs(fract(coord * 0.1 - 0.5) - 0.5) / (perPixel * 0.1), 1.5);
  vec2 axis = 1.0 - clamp(abs(coord) / perPixel - 0.5, 0.0, 1.0);  // x: on the Z axis (x = 0), y: on the X axis (z = 0)
  vec3 color = vec3(0.45);
  float alpha = max(minor * 0.35, major * 0.6);
  color = mix(color, vec3(0.85, 0.25, 0.25), axis.y);
  alpha = max(alpha, 0.8 * axis.y);
  color = mix(color, vec3(0.25, 0.4, 0.9), axis.x);
  alpha = max(alpha, 0.8 * axis.x);
  alpha *= fade;
  if (alpha < 0.004) discard;
  outColor = vec4(color, alpha);
}
