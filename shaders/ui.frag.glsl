#version 450
// Dear ImGui's pixels: the vertex colour times the font atlas's coverage. The
// atlas is alpha only (R8) and sampled nearest: glyphs sit on whole pixels at
// 1:1, so this matches linear filtering for text and costs one texel fetch on
// CPU devices (lavapipe) instead of four and their weights.
layout(set = 0, binding = 0) uniform sampler2D atlas;
layout(location = 0) in vec4 inColor;
layout(location = 1) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() { outColor = inColor * vec4(1.0, 1.0, 1.0, texture(atlas, inUv).r); }
