// Blend shapes (glTF morph targets) before skinning, as
// engine/core/rig/morph_targets.cpp computes them on the CPU:
// p = p0 + sum_t w_t dp_t, n = n0 + sum_t w_t dn_t (normalised after skinning).
// The mesh's deltas are its own descriptor set (AM_MORPH_SET); the draw's
// active (target, weight) pairs sit in the frame's joint buffer, read here as
// floats (the same binding as joints[], shared_constants.h). A draw without
// active targets (pc.morphCount == 0) skips it all: one uniform branch.
// Needs pc (mesh_push.glsl) and shared_constants.h first.
layout(set = AM_MORPH_SET, binding = AM_MORPH_BINDING_DELTAS, std430) readonly buffer MorphDeltas {
  float morphDeltas[];
};
layout(set = 0, binding = AM_BINDING_JOINTS, std430) readonly buffer JointFloats {
  float jointFloats[];
};

void amMorphVertex(uint v, inout vec3 p, inout vec3 n) {
  if (pc.morphCount == 0u) return;
  vec3 dp = vec3(0.0), dn = vec3(0.0);
  for (uint i = 0u; i < pc.morphCount; ++i) {
    uint t = floatBitsToUint(jointFloats[pc.morphOffset + 2u * i]);
    float w = jointFloats[pc.morphOffset + 2u * i + 1u];
    uint b = (t * pc.morphVertexCount + v) * uint(AM_MORPH_DELTA_FLOATS);
    dp += w * vec3(morphDeltas[b], morphDeltas[b + 1u], morphDeltas[b + 2u]);
    dn += w * vec3(morphDeltas[b + 3u], morphDeltas[b + 4u], morphDeltas[b + 5u]);
  }
  p += dp;
  vec3 nm = n + dn;
  n = dot(nm, nm) > 1e-24 ? nm : n;
}
