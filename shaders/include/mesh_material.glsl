// The base colour of a character mesh's pixel in linear light: the material's
// factor (pc.baseLinear, or the viewport grey for meshes without colour), times
// its base colour texture (sRGB image: sampling returns linear) when the draw
// sets AM_DRAW_TEXTURED, times the vertex colour (COLOR_0) with AM_DRAW_VERTEX_COLOR.
// Needs shared_constants.h and mesh_push.glsl first.
#include "transition_constants.h"
// False (a transition pipeline whose draws have no stand-in colour): inStandinColor is not read.
layout(constant_id = AM_SPEC_STANDIN_COLOR) const bool amStandinColored = true;

layout(set = AM_MATERIAL_SET, binding = AM_MATERIAL_BINDING_BASE_COLOR) uniform sampler2D baseColorTexture;

layout(location = 2) in vec2 inTexcoord0;
layout(location = 3) in vec4 inColor0;
layout(location = 4) in vec4 inStandinColor;  // a transition's stand-in colour (rgb) and alpha (a)

// Then faded into a transition's stand-in colour by its alpha (include/material_vertex.glsl).
vec3 amMaterialBase() {
  vec3 base = pc.baseLinear.rgb;
  if ((pc.flags & AM_DRAW_TEXTURED) != 0u) base *= texture(baseColorTexture, inTexcoord0).rgb;
  if ((pc.flags & AM_DRAW_VERTEX_COLOR) != 0u) base *= inColor0.rgb;
  return amStandinColored ? mix(base, inStandinColor.rgb, inStandinColor.a) : base;
}
