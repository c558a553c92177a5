#version 450
// Coloured line lists (skeleton overlay, bounds, axis indicator).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec4 inColor;

layout(push_constant) uniform LinePush {
  mat4 viewProj;
} pc;

layout(location = 0) out vec4 outColor;

void main() {
  outColor = inColor;
  gl_Position = pc.viewProj * vec4(inPosition, 1.0);
}
