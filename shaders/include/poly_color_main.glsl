// Fine pass 4 (only for a program whose primitives carry colours, GpuPolygonizer::Impl::colorTable):
// the surface colour of every vertex, the CPU's SurfaceColorEvaluator (engine/core/field/surface_color.h,
// docs/blobtree.md "Colour") at the vertex: the program's ops run again over (value, colour) pairs.
//   * Prims: sum: each primitive's colour weighted by max(p, 0) (none weighs: the first primitive's);
//     union (max): the colour of the largest, the first primitive's while none exceeds 0;
//   * Sum: the operands' colours weighted by max(v, 0); Max / Min: the colour of the operand taken;
//   * HyperBlend: weights (v / top)^q; Difference, Remap: the kept operand's colour;
//   * R-union, R-intersection, bounded blend: the partial derivatives (those > 0) as weights;
//   * where every weight is 0 the first operand's colour stays; a constant is clay;
//   * a map subtree none of whose primitives reaches the vertex's block: its value where none
//     contributes, with its colour there (the CPU's ColorProgram::emptyColor).
// One vertex per invocation (four dispatches of the normals pass's arguments, push constant x = k:
// vertex 4 i + k). The program walked is program A, whole, with the vertex's block primitive mask
// (positions[].w, as the normals pass): a primitive outside the block contributes 0 there, so it
// gives no weight either; or a colour program packed after it (GpuField::colors: the same surface,
// finer colours; push constant y its first op record, z its op count, w its threshold's bits),
// every primitive of it walked (the block masks are A's).
// The colour table (P.colorPass.x, a pool index) holds one vec4 per op of the program walked (the colour
// of the subtree it closes where no primitive contributes), then one per primitive (its colour).
// Out: normals[v].w = the colour's RGBA8 bits tagged AM_POLY_COLOR_TAG (poly_constants.h).

bool gAllPrimitives;  // a colour program of its own: every primitive walked
#define AM_BLOCK_MASK_WORD(maskBase, word_) (gAllPrimitives ? ~0u : blockMask[(maskBase) + (word_)])

#include "poly_common.glsl"
#include "poly_field.glsl"

#define AM_FIELD_V AM_POLY_NORMAL_V
#include "poly_field_batch.glsl"
#include "poly_field_gradient.glsl"

layout(local_size_x = AM_POLY_WG_NORMALS) in;
layout(push_constant) uniform ColorPush { uvec4 pc; };  // x: which vertex of each invocation's four

layout(set = 0, binding = AM_PB_POSITIONS, std430) readonly buffer Positions { vec4 positions[]; };
layout(set = 0, binding = AM_PB_NORMALS, std430) buffer Normals { vec4 normals[]; };

uint gColorTable, gOpCount;
vec3 opEmptyColor(uint op) { return POOLF(gColorTable + op).xyz; }
vec3 primColor(uint globalId) { return POOLF(gColorTable + gOpCount + globalId).xyz; }

// One primitive's value at q (class cls, pool record r): the kernels of the value interpreter.
float primitiveValue(uint cls, uint r, vec3 q, float T) {
  if (cls == AM_PRIM_CONVOLUTION)
    return convolution4(vec4(q.x), vec4(q.y), vec4(q.z), POOLF(r), POOLF(r + 1u), POOLF(r + 2u)).x;
  if (cls == AM_PRIM_SKELETAL) return skeletalValue(r, q);
  return capsuleValue(r, q, T);
}

// Blend of stack entries base .. base + n - 1 (xyz colour, w value) with weights w[k] (those > 0);
// false (nothing changed) when none weighs.
vec4 gSt[AM_POLY_MAX_STACK];
float gW[AM_POLY_MAX_STACK];
bool blendWeighted(int base, int n) {
  float sum = 0.0;
  vec3 c = vec3(0.0);
  for (int k = 0; k < n; ++k) {
    if (!(gW[k] > 0.0)) continue;
    sum += gW[k];
    c += gW[k] * gSt[base + k].xyz;
  }
  if (!(sum > 0.0)) return false;
  gSt[base].xyz = c / sum;
  return true;
}

// A Prims op (records op0) at q: its value and colour.
vec4 primsColor(uvec4 op0, uint opIndex, uint maskBase, vec3 q, float T) {
  uint cls = (op0.x >> 8) & 0xffu;
  bool cmax = ((op0.x >> 16) & 1u) != 0u;
  uint stride = cls == AM_PRIM_CONVOLUTION ? AM_REC_CONV : cls == AM_PRIM_SKELETAL ? AM_REC_SKEL : AM_REC_CAPSULE;
  vec3 first = opEmptyColor(opIndex);
  float v = 0.0, wsum = 0.0;
  vec3 c = cmax ? first : vec3(0.0);
  for (uint k = 0u; k < op0.z; ++k) {
    if (!primActive(maskBase, op0.w + k)) continue;
    float one = primitiveValue(cls, op0.y + k * stride, q, T);
    vec3 ck = primColor(op0.w + k);
    if (cmax) {
      if (one > v) {
        v = one;
        c = ck;
      }
    } else {
      float w = max(one, 0.0);
      v += one;
      wsum += w;
      c += w * ck;
    }
  }
  if (!cmax) c = wsum > 0.0 ? c / wsum : first;
  return vec4(c, v);
}

// An operator over stack entries [base, base + n): value and colour into gSt[base].
void operatorColor(uint code, int base, int n, uint prm, float T) {
  float v0 = gSt[base].w;
  if (code == AM_OP_SUM) {
    float v = 0.0;
    for (int k = 0; k < n; ++k) {
      v += gSt[base + k].w;
      gW[k] = max(gSt[base + k].w, 0.0);
    }
    blendWeighted(base, n);
    v0 = v;
  } else if (code == AM_OP_MAX || code == AM_OP_MIN) {
    for (int k = 1; k < n; ++k) {
      float vk = gSt[base + k].w;
      if (code == AM_OP_MAX ? vk > v0 : vk < v0) {
        v0 = vk;
        gSt[base].xyz = gSt[base + k].xyz;
      }
    }
  } else if (code == AM_OP_HYPERBLEND) {
    float q = paramAt(prm), top = 0.0;
    for (int k = 0; k < n; ++k) top = max(top, gSt[base + k].w);
    for (int k = 0; k < n; ++k) gW[k] = gSt[base + k].w > 0.0 ? pow(gSt[base + k].w / top, q) : 0.0;
    vec4 sum = vec4(0.0);
    for (int k = 0; k < n; ++k) {
      float vk = gSt[base + k].w;
      sum.x += vk > 0.0 ? pow(vk, q) : 0.0;
    }
    blendWeighted(base, n);
    v0 = sum.x > 0.0 ? pow(sum.x, 1.0 / q) : 0.0;
  } else if (code == AM_OP_DIFFERENCE) {
    v0 = min(v0, 2.0 * T - gSt[base + 1].w);
  } else if (code == AM_OP_RUNION || code == AM_OP_RINTERSECTION) {
    vec4 r, d1, d2;
    rFunctionPartials(vec4(v0 - T), vec4(gSt[base + 1].w - T), code == AM_OP_RUNION ? 1.0 : -1.0, r, d1, d2);
    gW[0] = d1.x;
    gW[1] = d2.x;
    blendWeighted(base, 2);
    float s1 = v0 - T, s2 = gSt[base + 1].w - T;
    v0 = T + (code == AM_OP_RUNION ? rUnion4(vec4(s1), vec4(s2)).x : rIntersection4(vec4(s1), vec4(s2)).x);
  } else if (code == AM_OP_BOUNDEDBLEND) {
    vec4 d1, d2, d3;
    vec4 r = boundedBlendGrad(vec4(v0 - T), vec4(gSt[base + 1].w - T), vec4(gSt[base + 2].w - T), paramAt(prm),
                              paramAt(prm + 1u), paramAt(prm + 2u), paramAt(prm + 3u), d1, d2, d3);
    gW[0] = d1.x;
    gW[1] = d2.x;
    blendWeighted(base, 2);  // the bounding solid gives no colour
    v0 = T + r.x;
  } else if (code == AM_OP_REMAP) {
    v0 = amRemap(v0, paramAt(prm), paramAt(prm + 1u), T);
  }
  gSt[base].w = v0;
}

// The colour of program A at p (its ops from opBegin, opCount of them).
vec3 programColor(uint opBegin, uint opCount, float T, uint maskBase, vec3 p) {
  vec3 saved[AM_POLY_MAX_MAP_DEPTH];
  vec3 q = p;
  int sp = 0, level = 0;
  for (uint i = 0u; i < opCount; ++i) {
    uint o = opBegin + i * AM_REC_OP;
    uvec4 op0 = POOLU(o);
    uint code = op0.x & 0xffu;
    if (code == AM_OP_PRIMS) {
      gSt[sp++] = primsColor(op0, i, maskBase, q, T);
    } else if (code == AM_OP_CONST) {
      gSt[sp++] = vec4(opEmptyColor(i), uintBitsToFloat(POOLU(o + 1u).z));
    } else if (code == AM_OP_BEGINMAP) {
      uvec4 op1 = POOLU(o + 1u);
      if (!anyPrimActive(maskBase, op0.w, op0.y)) {
        gSt[sp++] = vec4(opEmptyColor(i + op1.w), uintBitsToFloat(op1.z));
        i += op1.w;
        continue;
      }
      saved[level++] = q;
      q = mapToLocal(op1.y, q);
    } else if (code == AM_OP_ENDMAP) {
      q = saved[--level];
    } else {
      int n = int(op0.z);
      int base = sp - n;
      operatorColor(code, base, n, POOLU(o + 1u).x, T);
      sp = base + 1;
    }
  }
  return sp > 0 ? gSt[0].xyz : opEmptyColor(0u);
}

void colorPass() {
  gColorTable = P.colorPass.x;
  gAllPrimitives = pc.y != 0u;
  uint opBegin = gAllPrimitives ? pc.y : P.progA.x;
  gOpCount = gAllPrimitives ? pc.z : P.progA.y;
  float T = gAllPrimitives ? uintBitsToFloat(pc.w) : P.thresholds.x;
  uint total = min(control[AM_CTL_VERTICES], P.caps.x);
  uint v = 4u * gl_GlobalInvocationID.x + pc.x;
  if (v >= total || gColorTable == 0u) return;
  vec4 q = positions[v];
  vec3 c = clamp(programColor(opBegin, gOpCount, T, floatBitsToUint(q.w), q.xyz), 0.0, 1.0);
  uint bits = (packUnorm4x8(vec4(c, 0.0)) & 0x00ffffffu) | (AM_POLY_COLOR_TAG << 24);
  normals[v].w = uintBitsToFloat(bits);
}

void main() {
  colorPass();
  flagCutLoops(AM_OVERFLOW_CUT_COLORS);
}
