// Linear blend skinning with up to 8 influences, as glTF defines it and
// engine/core/rig/skinning.cpp computes it: skin = sum_k w_k * joint[j_k]
// (joints beyond the draw's joint count ignored). Needs the Joints buffer
// (joints[]) and the mesh push constants (pc, mesh_push.glsl) declared first.
void amAccumulateSkin(inout mat4 skin, uvec4 j, vec4 w) {
  for (int k = 0; k < 4; ++k)
    if (w[k] != 0.0 && j[k] < pc.jointCount) skin += w[k] * joints[pc.jointOffset + j[k]];
}

mat4 amSkinMatrix(uvec4 j0, vec4 w0, uvec4 j1, vec4 w1) {
  mat4 skin = mat4(0.0);
  amAccumulateSkin(skin, j0, w0);
  amAccumulateSkin(skin, j1, w1);
  return skin;
}
