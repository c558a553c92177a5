#version 450
#extension GL_GOOGLE_include_directive : require
// The transition of include/transition.glsl evaluated by compute, with the
// positions and normals read back (engine/gpu/transition/transition_evaluator.h): what
// the tests compare with the CPU transition, and what the bench times.
// pc.flags holds the vertex count.
#include "shared_constants.h"
#include "transition_constants.h"

layout(local_size_x = AM_TRE_WORKGROUP) in;

layout(set = 0, binding = AM_BINDING_JOINTS, std430) readonly buffer Joints {
  mat4 joints[];
};

struct Vertex {
  vec4 position;
  vec4 normal;
  uvec4 joints0;
  uvec4 joints1;
  vec4 weights0;
  vec4 weights1;
};
layout(set = 0, binding = AM_TRE_BINDING_VERTICES, std430) readonly buffer Vertices {
  Vertex vertices[];
};
layout(set = 0, binding = AM_TRE_BINDING_STANDIN, std430) readonly buffer Standin {
  vec4 standin[];  // 2 per vertex: (dp, m), (n~, 0)
};
layout(set = 0, binding = AM_TRE_BINDING_OUTPUT, std430) writeonly buffer Output {
  vec4 outputs[];  // 2 per vertex: world position, world unit normal
};

#include "mesh_push.glsl"
#include "skinning.glsl"
#include "transition.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.flags) return;
  Vertex v = vertices[i];
  vec4 wp;
  vec3 wn;
  amTransitionVertex(v.position.xyz, v.normal.xyz, v.joints0, v.weights0, v.joints1, v.weights1, standin[2u * i],
                     standin[2u * i + 1u].xyz, wp, wn);
  float l = length(wn);
  outputs[2u * i] = vec4(wp.xyz / wp.w, 1.0);
  outputs[2u * i + 1u] = vec4(l > 0.0 ? wn / l : vec3(0, 1, 0), 0.0);
}
