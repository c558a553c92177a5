// Constants shared by the C++ renderer and the GLSL shaders: included by both
// (GLSL through glslang's -I), so bindings, limits and flags are defined once.
// Only preprocessor definitions and, for C++, typed mirrors below.
#ifndef ANIMORPH_SHARED_CONSTANTS_H
#define ANIMORPH_SHARED_CONSTANTS_H

// Descriptor set 0 of every scene pipeline.
#define AM_BINDING_FRAME 0   // uniform buffer: FrameUniforms (shaders/include/frame.glsl)
#define AM_BINDING_JOINTS 1  // storage buffer: mat4 joint matrices of every draw of the frame

// Vertex input bindings / locations of a GPU mesh (one buffer per stream).
#define AM_VERTEX_POSITION 0
#define AM_VERTEX_NORMAL 1
#define AM_VERTEX_JOINTS0 2
#define AM_VERTEX_JOINTS1 3
#define AM_VERTEX_WEIGHTS0 4
#define AM_VERTEX_WEIGHTS1 5
#define AM_VERTEX_PAINT_WEIGHT 6  // weight-map overlay only: one float per vertex (its own buffer)
// Material streams of a GPU mesh (after the transition's stand-in binding, 6 and 7):
#define AM_VERTEX_TEXCOORD0 8  // vec2: the base colour texture's coordinates ((0, 0) without a texture)
#define AM_VERTEX_COLOR0 9     // vec4: glTF COLOR_0 ((1, 1, 1, 1) without one)

// Joint influences per vertex (two sets of four, glTF JOINTS_0/1, WEIGHTS_0/1).
#define AM_MAX_INFLUENCES 8

// Blend shapes (glTF morph targets) in the skinned vertex shaders
// (shaders/include/morph_targets.glsl): each mesh with targets has its own
// descriptor set AM_MORPH_SET holding its deltas (binding AM_MORPH_BINDING_DELTAS:
// 6 floats per target and vertex, position then normal delta, target-major);
// a mesh without targets is drawn with a one-element placeholder set. The
// draw's active targets (non-zero weights) are (target index, weight) pairs in
// the frame's joint buffer; at most AM_MAX_ACTIVE_MORPH_TARGETS per draw: a draw
// with more keeps the ones of largest |weight| (the CPU path uses them all).
#define AM_MORPH_SET 2
#define AM_MORPH_BINDING_DELTAS 0
#define AM_MORPH_DELTA_FLOATS 6
#define AM_MAX_ACTIVE_MORPH_TARGETS 64

// Materials (shaders/include/mesh_material.glsl): set AM_MATERIAL_SET binds the
// draw's base colour texture (a 1x1 white placeholder when it has none); the
// factor rides in MeshPush.baseLinear.
#define AM_MATERIAL_SET 3
#define AM_MATERIAL_BINDING_BASE_COLOR 0

// MeshPush.flags bits.
#define AM_DRAW_SELECTED 1u   // tint and rim-light the mesh
#define AM_DRAW_WIREFRAME 2u  // wireframe pass: flat colour, depth pulled toward the camera
#define AM_DRAW_TEXTURED 256u      // multiply the base colour by the material's texture (set AM_MATERIAL_SET)
#define AM_DRAW_VERTEX_COLOR 512u  // multiply the base colour by the vertex colour (AM_VERTEX_COLOR0)

// Frames the CPU may record ahead of the GPU (ring buffers have this many slots).
#define AM_FRAMES_IN_FLIGHT 2

#ifdef __cplusplus
#include <cstdint>
namespace animorph::gpu {
inline constexpr uint32_t kBindingFrame = AM_BINDING_FRAME;
inline constexpr uint32_t kBindingJoints = AM_BINDING_JOINTS;
inline constexpr uint32_t kMaxInfluences = AM_MAX_INFLUENCES;
inline constexpr uint32_t kVertexPaintWeight = AM_VERTEX_PAINT_WEIGHT;
inline constexpr uint32_t kDrawSelected = AM_DRAW_SELECTED;
inline constexpr uint32_t kDrawWireframe = AM_DRAW_WIREFRAME;
inline constexpr uint32_t kFramesInFlight = AM_FRAMES_IN_FLIGHT;
inline constexpr uint32_t kMorphSet = AM_MORPH_SET;
inline constexpr uint32_t kMaterialSet = AM_MATERIAL_SET;
inline constexpr uint32_t kVertexTexcoord0 = AM_VERTEX_TEXCOORD0;
inline constexpr uint32_t kVertexColor0 = AM_VERTEX_COLOR0;
inline constexpr uint32_t kDrawTextured = AM_DRAW_TEXTURED;
inline constexpr uint32_t kDrawVertexColor = AM_DRAW_VERTEX_COLOR;
inline constexpr uint32_t kMorphDeltaFloats = AM_MORPH_DELTA_FLOATS;
inline constexpr uint32_t kMaxActiveMorphTargets = AM_MAX_ACTIVE_MORPH_TARGETS;
}  // namespace animorph::gpu
#endif

#endif  // ANIMORPH_SHARED_CONSTANTS_H
