// Fine pass 3: the normal of every vertex of the mesh, -grad f / |grad f|, four
// vertices per invocation over the whole vertex buffer (indirect dispatch from
// the args pass), so no lane idles for blocks with few vertices, as it did when
// each block's workgroup took its own. Analytic gradient as the CPU's
// (poly_field_gradient.glsl); for HyperBlend and non-affine maps a tetrahedral
// difference stencil (4 points at d (+-1, +-1, +-1) with an even number of minus
// signs, d = the normal step: second order like central differences). The
// emit pass wrote each vertex's block primitive mask into positions[].w; an
// invocation's vertices may lie in different blocks, so the primitive loop
// walks the union of their masks: a primitive outside a block contributes
// exactly 0 there, so the extra ones change nothing. Where the gradient
// vanishes the emit pass's edge direction stays.

uvec4 gMaskBases;  // the primitive masks of the invocation's four vertices
#define AM_BLOCK_MASK_WORD(maskBase, word_)                                                               \
  (blockMask[gMaskBases.x + (word_)] | blockMask[gMaskBases.y + (word_)] | blockMask[gMaskBases.z + (word_)] | \
   blockMask[gMaskBases.w + (word_)])

#include "poly_common.glsl"
#include "poly_field.glsl"

#define AM_FIELD_V AM_POLY_NORMAL_V
#include "poly_field_batch.glsl"
#include "poly_field_gradient.glsl"

layout(local_size_x = AM_POLY_WG_NORMALS) in;
layout(push_constant) uniform NormalsPush { uvec4 pc; };  // x: AM_NORMALS_* (which of the four vertices)

layout(set = 0, binding = AM_PB_POSITIONS, std430) readonly buffer Positions { vec4 positions[]; };
layout(set = 0, binding = AM_PB_NORMALS, std430) buffer Normals { vec4 normals[]; };

// Writes -g / |g| unless the gradient vanishes (then the emit pass's normal stays).
void writeNormal(uint v, vec3 g) {
  float len = length(g);
  if (len > 1e-20 && !isinf(len) && !isnan(len)) normals[v] = vec4(-g / len, 0.0);
}

// Gradient from the tetrahedral stencil values f at offsets d k0..k3 (see main).
vec3 stencilGradient(vec4 f) {
  return vec3(dot(f, vec4(1, -1, -1, 1)), dot(f, vec4(-1, -1, 1, 1)), dot(f, vec4(-1, 1, -1, 1)));
}

// The region of the vertex whose block's primitive mask is at maskBase (0 without region lists).
uint vertexRegion(uint maskBase) {
  if (P.regions.x == 0u) return 0u;
  return regionOf(blockCoord(maskBase / max(P.modes.y, 1u)));
}

// Normals of the invocation's vertices that lie in region `region`, with its op lists.
// Only the `handled` vertices are this dispatch's; the stencil evaluates the pairs [hBegin, hEnd).
void normalsIn(uint region, uvec4 supers, uint v0, uint total, vec4 q0, vec4 q1, vec4 q2, vec4 q3, bvec4 handled,
               uint hBegin, uint hEnd) {
  selectRegionOps(region);
  bvec4 mine = bvec4(uvec4(equal(supers, uvec4(region))) & uvec4(handled));
  if (AM_ANALYTIC_GRADIENT) {
    Grad4 g = fieldGrad(gMaskBases.x, vec4(q0.x, q1.x, q2.x, q3.x), vec4(q0.y, q1.y, q2.y, q3.y),
                        vec4(q0.z, q1.z, q2.z, q3.z));
    if (mine.x) writeNormal(v0, vec3(g.x[0], g.y[0], g.z[0]));
    if (mine.y && v0 + 1u < total) writeNormal(v0 + 1u, vec3(g.x[1], g.y[1], g.z[1]));
    if (mine.z && v0 + 2u < total) writeNormal(v0 + 2u, vec3(g.x[2], g.y[2], g.z[2]));
    if (mine.w && v0 + 3u < total) writeNormal(v0 + 3u, vec3(g.x[3], g.y[3], g.z[3]));
  } else {
    const float d = P.morph1.w;
    const vec3 k0 = vec3(1, -1, -1), k1 = vec3(-1, -1, 1), k2 = vec3(-1, 1, -1), k3 = vec3(1, 1, 1);
    for (uint h = hBegin; h < hEnd; ++h) {  // two vertices per evaluation (8 points)
      vec3 posA = h == 0u ? q0.xyz : q2.xyz, posB = h == 0u ? q1.xyz : q3.xyz;
      PointsV w;
      AM_SET_POINT(w, 0, 0, posA + d * k0) AM_SET_POINT(w, 0, 1, posA + d * k1)
      AM_SET_POINT(w, 0, 2, posA + d * k2) AM_SET_POINT(w, 0, 3, posA + d * k3)
      AM_SET_POINT(w, 1, 0, posB + d * k0) AM_SET_POINT(w, 1, 1, posB + d * k1)
      AM_SET_POINT(w, 1, 2, posB + d * k2) AM_SET_POINT(w, 1, 3, posB + d * k3)
      vec4 f[AM_FIELD_V];
      fieldV(gMaskBases.x, w, f);
      uint va = v0 + 2u * h;
      if ((h == 0u ? mine.x : mine.z) && va < total) writeNormal(va, stencilGradient(f[0]));
      if ((h == 0u ? mine.y : mine.w) && va + 1u < total) writeNormal(va + 1u, stencilGradient(f[1]));
    }
  }
}

void normalsPass() {
  uint total = min(control[AM_CTL_VERTICES], P.caps.x);
  uint v0 = 4u * gl_GlobalInvocationID.x;
  uint last = max(total, 1u) - 1u;
  vec4 q0 = positions[min(v0, last)], q1 = positions[min(v0 + 1u, last)];
  vec4 q2 = positions[min(v0 + 2u, last)], q3 = positions[min(v0 + 3u, last)];
  gMaskBases = uvec4(floatBitsToUint(q0.w), floatBitsToUint(q1.w), floatBitsToUint(q2.w), floatBitsToUint(q3.w));
  if (v0 >= total) return;
  // With per-region op lists the four vertices may lie in up to four regions: one evaluation per
  // distinct region (nearly always one: the vertices are in block order), each writing its own
  // vertices. The loop's trip count is the count of distinct ones (an `if` would not skip
  // the evaluations on lavapipe).
  uvec4 supers = uvec4(vertexRegion(gMaskBases.x), vertexRegion(gMaskBases.y),
                       vertexRegion(gMaskBases.z), vertexRegion(gMaskBases.w));
  // One vertex per dispatch (AM_NORMALS_VERTEX + k, programs near lavapipe's loop limit with
  // region lists): the other vertices take its region and mask, so they add no walk (and are not
  // written); the stencil evaluates only its pair.
  bvec4 handled = bvec4(true);
  uint hBegin = 0u, hEnd = 2u;
  if (pc.x != AM_NORMALS_ALL) {
    uint k = pc.x - AM_NORMALS_VERTEX;
    if (v0 + k >= total) return;
    handled = equal(uvec4(0u, 1u, 2u, 3u), uvec4(k));
    supers = uvec4(supers[k]);
    gMaskBases = uvec4(gMaskBases[k]);
    hBegin = k >> 1;
    hEnd = hBegin + 1u;
  }
  uvec4 pending = uvec4(supers.x, 0u, 0u, 0u);
  uint n = 1u;
  if (supers.y != supers.x) pending[n++] = supers.y;
  if (supers.z != supers.x && supers.z != supers.y) pending[n++] = supers.z;
  if (supers.w != supers.x && supers.w != supers.y && supers.w != supers.z) pending[n++] = supers.w;
  for (uint k = 0u; k < n; ++k) normalsIn(pending[k], supers, v0, total, q0, q1, q2, q3, handled, hBegin, hEnd);
}

void main() {
  normalsPass();
  flagCutLoops(AM_OVERFLOW_CUT_NORMALS);
}
