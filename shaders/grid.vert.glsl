#version 450
#extension GL_GOOGLE_include_directive : require
// Ground grid as geometry: each instance is one grid line on y = 0, drawn as a
// screen-space quad a few pixels wide (6 vertices, no vertex buffer). Instances
// 0 .. 2N are the lines of constant z (along x), 2N + 1 .. 4N + 1 those of
// constant x, N = frame.gridCenter.w, around frame.gridCenter. A line is the
// chord of a disk around the camera's foot: the fade radius, and for minor and
// major lines also the distance where parallel lines come closer than a few
// pixels on screen (seen at a grazing angle), so distant lines are not drawn
// over each other. On CPU renderers a full-plane grid shader cost more than the
// rest of the viewport: only the lines' pixels are shaded now.
#include "frame.glsl"

layout(location = 0) out vec3 outWorldPos;              // on the line's centre
layout(location = 1) noperspective out float outAcross; // signed pixels from the centre line
layout(location = 2) flat out vec4 outStyle;            // rgb, alpha before fades
layout(location = 3) flat out vec2 outShape;            // x: half width (px), y: LOD radius (m)

const float kMinPx = 3.0;  // closest on-screen spacing of parallel lines that is drawn

void hide() {
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the view volume: the quad is clipped away
}

void main() {
  int n = int(frame.gridCenter.w);
  int instance = gl_InstanceIndex;
  bool alongX = instance <= 2 * n;  // a line of constant z
  int i = (alongX ? instance : instance - (2 * n + 1)) - n;
  float cell = frame.grid.x;
  float c = (alongX ? frame.gridCenter.z : frame.gridCenter.x) + float(i) * cell;
  int k = int(round(c / cell));
  bool axis = k == 0, major = k % 10 == 0;
  // Style, as the coverage of the former per-pixel grid: minor 1 px at 0.35, major 1.5 px at 0.6,
  // the X axis (z = 0) red and the Z axis (x = 0) blue, 2 px at 0.8.
  vec3 color = axis ? (alongX ? vec3(0.85, 0.25, 0.25) : vec3(0.25, 0.4, 0.9)) : vec3(0.45);
  float alpha = axis ? 0.8 : major ? 0.6 : 0.35;
  float halfWidth = axis ? 1.0 : major ? 0.75 : 0.5;
  // Radius of the disk around the camera's foot where the line is drawn.
  vec3 eye = frame.cameraPos.xyz;
  float h = max(abs(eye.y), 1e-3);
  float spacing = major ? 10.0 * cell : cell;
  float radius = frame.grid.z;  // fade end
  if (!axis) radius = min(radius, sqrt(spacing * frame.viewportPx.z * h / kMinPx));
  outStyle = vec4(color, alpha);
  outShape = vec2(halfWidth, radius);
  float r2 = radius * radius - h * h;  // squared horizontal radius
  float off = c - (alongX ? eye.z : eye.x);
  float half2 = r2 - off * off;
  if (half2 <= 0.0) {
    hide();
    return;
  }
  float halfLen = sqrt(half2), mid = alongX ? eye.x : eye.z;
  vec3 a = alongX ? vec3(mid - halfLen, 0.0, c) : vec3(c, 0.0, mid - halfLen);
  vec3 b = alongX ? vec3(mid + halfLen, 0.0, c) : vec3(c, 0.0, mid + halfLen);
  // Clip the segment to the near plane (z >= 0 in Vulkan clip space).
  vec4 ca = frame.viewProj * vec4(a, 1.0), cb = frame.viewProj * vec4(b, 1.0);
  if (ca.z < 0.0 && cb.z < 0.0) {
    hide();
    return;
  }
  if (ca.z < 0.0) {
    float t = ca.z / (ca.z - cb.z);
    ca = mix(ca, cb, t);
    a = mix(a, b, t);
  } else if (cb.z < 0.0) {
    float t = cb.z / (cb.z - ca.z);
    cb = mix(cb, ca, t);
    b = mix(b, a, t);
  }
  // Screen-space quad: the segment widened by half the width plus the anti-aliasing pixel.
  vec2 halfPx = 0.5 * frame.viewportPx.xy;
  vec2 sa = ca.xy / ca.w * halfPx, sb = cb.xy / cb.w * halfPx;
  vec2 d = sb - sa;
  float len = length(d);
  if (len < 1e-4) {
    hide();
    return;
  }
  vec2 normal = vec2(-d.y, d.x) / len;
  const int ends[6] = int[](0, 1, 1, 0, 1, 0);
  const float sides[6] = float[](-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
  int corner = gl_VertexIndex % 6;
  bool atB = ends[corner] == 1;
  vec4 clip = atB ? cb : ca;
  float across = sides[corner] * (halfWidth + 0.5);
  clip.xy += normal * across / halfPx * clip.w;
  gl_Position = clip;
  outWorldPos = atB ? b : a;
  outAcross = across;
}
