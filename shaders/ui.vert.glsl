#version 450
// Dear ImGui's draw lists (engine/gpu/present/imgui_vulkan.cpp): 2D positions in display
// pixels mapped to clip space by a scale and an offset.
layout(location = 0) in vec2 inPos;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec4 inColor;  // R8G8B8A8_UNORM
layout(push_constant) uniform UiPush { vec4 scaleOffset; } pc;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec2 outUv;

void main() {
  outColor = inColor;
  outUv = inUv;
  gl_Position = vec4(inPos * pc.scaleOffset.xy + pc.scaleOffset.zw, 0.0, 1.0);
}
