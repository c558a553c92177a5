// Push constants of the mesh pipelines (skinned mesh, wireframe, GPU-generated
// mesh); mirrors struct MeshPush in engine/gpu/render/scene_renderer.cpp.
layout(push_constant) uniform MeshPush {
  mat4 model;
  vec4 color;
  uint jointOffset;
  uint jointCount;
  uint flags;
  float depthPull;
  vec4 baseLinear;  // rgb: color.rgb in linear light (pow 2.2, taken on the CPU once per draw)
  // Blend shapes (morph_targets.glsl): the draw's active targets are morphCount
  // (target, weight) pairs at float morphOffset of the joint buffer; 0: none.
  uint morphOffset;
  uint morphCount;
  uint morphVertexCount;  // vertices of the mesh (the deltas' stride per target)
  uint morphPad;
} pc;
