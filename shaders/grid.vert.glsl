#version 450
#extension GL_GOOGLE_include_directive : require
// Ground grid: one quad on y = 0 around frame.gridCenter, no vertex buffer.
#include "frame.glsl"

layout(location = 0) out vec3 outWorldPos;

void main() {
  const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 c = corners[gl_VertexIndex] * frame.grid.w;
  vec3 p = vec3(frame.gridCenter.x + c.x, 0.0, frame.gridCenter.z + c.y);
  outWorldPos = p;
  gl_Position = frame.viewProj * vec4(p, 1.0);
}
