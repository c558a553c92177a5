// Constants of the GPU transition (collapse onto / expansion from the stand-in,
// shaders/include/transition.glsl) shared by engine/gpu/transition_renderer.cpp,
// transition_evaluator.cpp and the shaders. Only preprocessor definitions.
#ifndef ANIMORPH_TRANSITION_CONSTANTS_H
#define ANIMORPH_TRANSITION_CONSTANTS_H

// Extra vertex streams of a transition draw (after the mesh's AM_VERTEX_*).
#define AM_VERTEX_STANDIN_OFFSET 6  // vec4: dp_i (bind space), weight-map value m_i
#define AM_VERTEX_STANDIN_NORMAL 7  // vec4: n~_i (bind space, unit), the stand-in colour's bits
// The stand-in colour c~_i in AM_VERTEX_STANDIN_NORMAL's w: its bits are RGBA8 (unpackUnorm4x8's
// order, linear) with this tag in the top byte (0: no colour). With the tag the bits are a normal
// float in [0.5, 2), never a NaN or a denormal a vertex fetch could change.
#define AM_STANDIN_COLOR_TAG 63u
// Specialisation constant (a bool) of the transition pipelines' vertex and fragment stages: true
// where the draw's binding carries stand-in colours; false compiles the unpacking, the varying and
// the per-pixel fade out, so a transition without colours pays nothing for them.
#define AM_SPEC_STANDIN_COLOR 0

// Descriptor set 1 of the transition pipelines: the per-draw parameters
// (a storage buffer with a dynamic offset: lavapipe specialises shaders on
// uniform-buffer contents, see docs/gpu-polygonizer.md).
#define AM_TRANSITION_SET 1
#define AM_TRANSITION_BINDING_PARAMS 0

// Limits of the parameter block (engine/core/scene/transition_frame.h).
#define AM_TRANSITION_MAX_SEGMENTS 64
#define AM_TRANSITION_LUT_FLOATS 513  // kTransitionEasingIntervals + 1
#define AM_TRANSITION_LUT_VEC4 129

// TransitionParams.mode.x bits.
#define AM_TR_PER_VERTEX 1u   // alpha from the easing table and the weight map
#define AM_TR_EXPAND 2u       // alpha = 1 - table value
#define AM_TR_REPROJECT 4u    // Newton steps onto the posed stand-in above reprojectFrom
#define AM_TR_CAPSULES 8u     // primitives are skeletal segments (else convolution segments)
#define AM_TR_COMBINE_MAX 16u // capsule union: max of the primitives (else their sum)

// MeshPush.flags bits of dithered (screen-door) cross-fade draws: discard
// where a 4x4 Bayer threshold is not below the opacity (MeshPush.color.a);
// INVERT uses 1 - threshold, so two draws at opacities o and 1 - o cover
// complementary pixels.
#define AM_DRAW_DITHER 64u
#define AM_DRAW_DITHER_INVERT 128u

// The compute evaluator (tests, bench): set 0 bindings beside AM_BINDING_JOINTS.
#define AM_TRE_BINDING_VERTICES 2  // storage: per vertex 6 vec4 (position, normal, joints0, joints1, weights0, weights1)
#define AM_TRE_BINDING_STANDIN 3   // storage: per vertex 2 vec4 (dp + m, n~)
#define AM_TRE_BINDING_OUTPUT 4    // storage: per vertex 2 vec4 (world position, world unit normal)
#define AM_TRE_WORKGROUP 64

#endif  // ANIMORPH_TRANSITION_CONSTANTS_H
