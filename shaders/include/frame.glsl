// Per-frame uniforms of the scene renderer (C++ mirror: FrameUniforms in
// engine/gpu/render/scene_renderer.cpp; std140).
#include "shared_constants.h"

layout(set = 0, binding = AM_BINDING_FRAME) uniform FrameUniforms {
  mat4 viewProj;
  mat4 view;
  vec4 cameraPos;    // xyz: eye in world space
  vec4 keyLightDir;  // xyz: unit direction towards the key light (world)
  vec4 grid;         // x: cell size (m), y: fade start (m), z: fade end (m), w: half extent (m)
  vec4 gridCenter;   // xyz: centre of the grid (on y = 0); w: N, lines on each side of it (grid.vert)
  vec4 selectColor;  // rgb: highlight of selected meshes, in linear light
  vec4 viewportPx;   // x, y: viewport size (px); z: focal length (px, vertical)
} frame;
