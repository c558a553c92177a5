#version 450
#extension GL_GOOGLE_include_directive : require
// Polygoniser pass "noise" (only when GpuPolygonizeSettings::noiseAmplitude != 0): moves every
// vertex along its normal by amplitude * solidNoise(frequency * p), as the CPU's
// displaceBySolidNoise (engine/core/poly/solid_noise.cpp: Perlin's improved noise, his
// permutation), after the normals pass, which took the normals at the undisplaced positions as
// the CPU does. Four vertices per invocation over the whole vertex buffer, dispatched with the
// normals pass's arguments. P.extra.y: amplitude (m); P.extra.z: frequency (1/m).
#include "poly_common.glsl"

layout(local_size_x = AM_POLY_WG_NORMALS) in;

layout(set = 0, binding = AM_PB_POSITIONS, std430) buffer Positions { vec4 positions[]; };
layout(set = 0, binding = AM_PB_NORMALS, std430) readonly buffer Normals { vec4 normals[]; };

// Perlin's permutation, uploaded after the marching-cubes table (solidNoisePermutation()).
layout(set = 0, binding = AM_PB_TABLE, std430) readonly buffer Tables {
  uvec4 mcCases[256];
  uint kPerm[256];
};

int perm(int i) { return int(kPerm[i & 255]); }
float fade(float t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
float lerpN(float t, float a, float b) { return a + t * (b - a); }
float grad(int hash, float x, float y, float z) {
  int h = hash & 15;
  float u = h < 8 ? x : y;
  float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) != 0 ? -u : u) + ((h & 2) != 0 ? -v : v);
}

float solidNoise(vec3 p) {
  vec3 f = floor(p);
  int X = int(f.x) & 255, Y = int(f.y) & 255, Z = int(f.z) & 255;
  float x = p.x - f.x, y = p.y - f.y, z = p.z - f.z;
  float u = fade(x), v = fade(y), w = fade(z);
  int A = perm(X) + Y, AA = perm(A) + Z, AB = perm(A + 1) + Z;
  int B = perm(X + 1) + Y, BA = perm(B) + Z, BB = perm(B + 1) + Z;
  return lerpN(w,
               lerpN(v, lerpN(u, grad(perm(AA), x, y, z), grad(perm(BA), x - 1.0, y, z)),
                     lerpN(u, grad(perm(AB), x, y - 1.0, z), grad(perm(BB), x - 1.0, y - 1.0, z))),
               lerpN(v, lerpN(u, grad(perm(AA + 1), x, y, z - 1.0), grad(perm(BA + 1), x - 1.0, y, z - 1.0)),
                     lerpN(u, grad(perm(AB + 1), x, y - 1.0, z - 1.0), grad(perm(BB + 1), x - 1.0, y - 1.0, z - 1.0))));
}

void main() {
  uint total = min(control[AM_CTL_VERTICES], P.caps.x);
  float amplitude = P.extra.y, frequency = P.extra.z;
  for (uint k = 0u; k < 4u; ++k) {
    uint v = 4u * gl_GlobalInvocationID.x + k;
    if (v >= total) break;
    vec4 q = positions[v];
    // w carries the block's primitive-mask offset (emit pass): kept.
    q.xyz += normals[v].xyz * (amplitude * solidNoise(q.xyz * frequency));
    positions[v] = q;
  }
}
