// The vertex inputs of a skinned mesh (position, normal, two sets of four
// joints and weights), the joint matrices and the mesh push constants, and the
// skinning functions over them (skinning.glsl), blend shapes first (morph_targets.glsl). Shared by mesh.vert,
// transition.vert and weight_overlay.vert; include after frame.glsl.
layout(location = AM_VERTEX_POSITION) in vec3 inPosition;
layout(location = AM_VERTEX_NORMAL) in vec3 inNormal;
layout(location = AM_VERTEX_JOINTS0) in uvec4 inJoints0;
layout(location = AM_VERTEX_JOINTS1) in uvec4 inJoints1;
layout(location = AM_VERTEX_WEIGHTS0) in vec4 inWeights0;
layout(location = AM_VERTEX_WEIGHTS1) in vec4 inWeights1;

layout(set = 0, binding = AM_BINDING_JOINTS, std430) readonly buffer Joints {
  mat4 joints[];
};

#include "mesh_push.glsl"
#include "skinning.glsl"
#include "morph_targets.glsl"
