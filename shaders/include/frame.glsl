// Per-frame uniforms of the scene renderer (C++ mirror: FrameUniforms in
// engine/gpu/scene_renderer.cpp; std140).
#include "shared_constants.h"

layout(set = 0, binding = AM_BINDING_FRAME) uniform FrameUniforms {
  mat4 viewProj;
  mat4 view;
  vec4 cameraPos;    // xyz: eye in world space
  vec4 keyLightDir;  // xyz: unit direction towards the key light (world)
  vec4 grid;         // x: cell size (m), y: fade start (m), z: fade end (m), w: half extent of the quad (m)
  vec4 gridCenter;   // xyz: centre of the grid quad (on y = 0)
  vec4 selectColor;  // rgb: highlight of selected meshes
} frame;
