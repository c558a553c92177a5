#version 450
#extension GL_GOOGLE_include_directive : require
// The particle view's spheres (ParticleSpheresDraw in engine/gpu/render/scene_renderer.h): one
// instance per particle, one triangle facing the eye through the sphere's centre, circumscribing
// its silhouette: the cone from the eye tangent to a sphere of radius r at distance d cuts that
// plane in a circle of radius r d / sqrt(d^2 - r^2), the triangle's inscribed circle. One
// triangle rather than a square's two: a CPU rasteriser shades each small triangle's 4x4 pixel
// blocks on its own, so two triangles over the same few pixels cost nearly twice as much.
// particle_sphere.frag ray-casts the sphere inside it. A sphere around the eye draws nothing. Each
// particle has its own colour (a converted shape's particles keep their surface's colours).
#include "frame.glsl"
#include "mesh_push.glsl"

layout(location = 0) in vec4 inSphere;  // xyz: centre (world), w: radius
layout(location = 1) in vec4 inColor;   // sRGB; alpha 0: the draw's colour (pc.baseLinear)

layout(location = 0) out vec3 outWorldPos;      // on the triangle
layout(location = 1) flat out vec4 outSphere;
layout(location = 2) flat out vec3 outBase;     // the particle's colour in linear light

void main() {
  // An equilateral triangle whose inscribed circle has radius 1 (counter-clockwise).
  const vec2 corners[3] = vec2[](vec2(0.0, 2.0), vec2(-1.7320508, -1.0), vec2(1.7320508, -1.0));
  const vec2 corner = corners[gl_VertexIndex];
  outSphere = inSphere;
  // pow(c, 2.2) as the draw colour's pc.baseLinear, once per vertex rather than per pixel.
  outBase = inColor.a > 0.5 ? pow(inColor.rgb, vec3(2.2)) : pc.baseLinear.rgb;
  const vec3 toCentre = inSphere.xyz - frame.cameraPos.xyz;
  const float d = length(toCentre), r = inSphere.w;
  if (!(r > 0.0) || d <= 1.0001 * r) {  // degenerate: outside the clip volume
    outWorldPos = inSphere.xyz;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  const vec3 f = toCentre / d;
  const vec3 cameraUp = vec3(frame.view[0][1], frame.view[1][1], frame.view[2][1]);
  vec3 right = cross(f, cameraUp);
  if (dot(right, right) < 1e-8) right = vec3(frame.view[0][0], frame.view[1][0], frame.view[2][0]);
  right = normalize(right);
  const vec3 up = cross(right, f);
  const float extent = r * d / sqrt(d * d - r * r);
  const vec3 p = inSphere.xyz + extent * (corner.x * right + corner.y * up);
  outWorldPos = p;
  gl_Position = frame.viewProj * vec4(p, 1.0);
}
