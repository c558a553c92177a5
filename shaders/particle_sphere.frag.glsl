#version 450
#extension GL_GOOGLE_include_directive : require
// A particle of the particle view as a sphere (particle_sphere.vert): the eye ray through the pixel
// meets the sphere or the pixel is discarded; the hit's depth is written (spheres cut each other
// and the meshes where they truly do) and it is shaded like a mesh (include/mesh_shading.glsl)
// with the sphere's normal, in the particle's colour. The ray's distance from the centre is taken
// from the perpendicular foot, not as |o - c|^2 - r^2 (which cancels when the eye is far from a
// small sphere).
#include "frame.glsl"

#include "mesh_push.glsl"
#include "mesh_shading.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) flat in vec4 inSphere;
layout(location = 2) flat in vec3 inBase;  // linear
layout(location = 0) out vec4 outColor;

void main() {
  const vec3 eye = frame.cameraPos.xyz;
  const vec3 dir = normalize(inWorldPos - eye);
  const vec3 toCentre = inSphere.xyz - eye;
  const float along = dot(toCentre, dir);     // distance to the foot of the perpendicular from the centre
  const vec3 off = toCentre - along * dir;    // foot to centre
  const float r = inSphere.w;
  const float h2 = r * r - dot(off, off);
  if (h2 < 0.0) discard;
  const vec3 hit = eye + (along - sqrt(h2)) * dir;
  const vec4 clip = frame.viewProj * vec4(hit, 1.0);
  gl_FragDepth = clip.z / clip.w;
  outColor = amShadeMeshBase(hit, (hit - inSphere.xyz) / r, inBase);
}
