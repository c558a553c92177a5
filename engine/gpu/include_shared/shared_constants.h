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

// Joint influences per vertex (two sets of four, glTF JOINTS_0/1, WEIGHTS_0/1).
#define AM_MAX_INFLUENCES 8

// MeshPush.flags bits.
#define AM_DRAW_SELECTED 1u   // tint and rim-light the mesh
#define AM_DRAW_WIREFRAME 2u  // wireframe pass: flat colour, depth pulled toward the camera

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
}  // namespace animorph::gpu
#endif

#endif  // ANIMORPH_SHARED_CONSTANTS_H
