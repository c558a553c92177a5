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
// the k-th quarter of the vertices). The program walked is program A, whole, with the vertex's block primitive mask
// (positions[].w, as the normals pass): a primitive outside the block contributes 0 there, so it
// gives no weight either; or a colour program packed after it (GpuField::colors: the same surface,
// finer colours; push constant y its first op record, z its op count, w its threshold's bits),
// every primitive of it walked (the block masks are A's).
// The colour table (P.colorPass.x, a pool index) holds one vec4 per op of the program walked (the colour
// of the subtree it closes where no primitive contributes), then one per primitive (its colour).
// With per-region op lists (P.colorPass.z = 1 + the regions' shift; 0: none) the walk is the
// vertex's region's list instead: program A's (the one the normals pass walks, P.regionLists.x) or
// the colour program's own (P.colorPass.w, built the same way for pairs of blocks: gpu_color_table.h),
// so its cost follows the ops and primitives near the vertex. A list is the CPU's specialised
// program (FieldProgram::specialise): where it dropped a subtree or a zero operand, its records
// carry the colour provenance the CPU's walk reads (gpu_region_op_lists.h): rule 1 a constant's
// colour, 2 a Sum's where no operand weighs, 3 an op's where its value is <= 0, each an op's empty
// colour of the whole program (the table's first part); a Prims op's fallback is its whole op's
// first primitive's colour, a skipped map's its map's empty colour (the table's maps, P.colorPass.y;
// the clay tone the word before). Colours: those of the whole walk, as the CPU's evaluateActive
// gives them (surface_color.h).
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

uint gColorTable, gOpCount;  // gOpCount: the whole program's ops (the table's first part)
bool gListWalk;               // the ops walked are a region's list (their records carry provenance)
vec3 opEmptyColor(uint op) { return POOLF(gColorTable + op).xyz; }
vec3 primColor(uint globalId) { return POOLF(gColorTable + gOpCount + globalId).xyz; }
vec3 mapEmptyColor(uint map) { return POOLF(P.colorPass.y + map).xyz; }
// A list op's provenance prov (bits 30-31 the rule, 0-29 one plus a whole-program op index): that
// op's empty colour; the clay tone without one.
vec3 ruleColor(uint prov) {
  uint ref = prov & 0x3fffffffu;
  return ref > 0u ? opEmptyColor(ref - 1u) : POOLF(P.colorPass.y - 1u).xyz;
}

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

// A Prims op (records op0) at q: its value and colour (first: its colour where none contributes).
vec4 primsColor(uvec4 op0, vec3 first, uint maskBase, vec3 q, float T) {
  uint cls = (op0.x >> 8) & 0xffu;
  bool cmax = ((op0.x >> 16) & 1u) != 0u;
  uint stride = cls == AM_PRIM_CONVOLUTION ? AM_REC_CONV : cls == AM_PRIM_SKELETAL ? AM_REC_SKEL : AM_REC_CAPSULE;
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

// An operator over stack entries [base, base + n): value and colour into gSt[base] (prov: the op's
// colour provenance, 0 but in a region's list).
void operatorColor(uint code, int base, int n, uint prm, float T, uint prov) {
  float v0 = gSt[base].w;
  if (code == AM_OP_SUM) {
    float v = 0.0;
    for (int k = 0; k < n; ++k) {
      v += gSt[base + k].w;
      gW[k] = max(gSt[base + k].w, 0.0);
    }
    if (!blendWeighted(base, n) && (prov >> 30) == 2u) gSt[base].xyz = ruleColor(prov);
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

// Stack entry s just pushed by an op of provenance prov: rule 3's colour where its value is <= 0.
void applyValueRule(uint prov, int s) {
  if ((prov >> 30) == 3u && !(gSt[s].w > 0.0)) gSt[s].xyz = ruleColor(prov);
}

// The colour of the program at p (its ops from opBegin, opCount of them: the whole program, or with
// gListWalk a region's list).
vec3 programColor(uint opBegin, uint opCount, float T, uint maskBase, vec3 p) {
  vec3 saved[AM_POLY_MAX_MAP_DEPTH];
  vec3 q = p;
  int sp = 0, level = 0;
  for (uint i = 0u; i < opCount; ++i) {
    uint o = opBegin + i * AM_REC_OP;
    uvec4 op0 = POOLU(o);
    uint code = op0.x & 0xffu;
    uvec4 op1 = POOLU(o + 1u);
    uint prov = gListWalk && code != AM_OP_BEGINMAP ? op1.w : 0u;  // a BeginMap's w is its skip
    if (code == AM_OP_PRIMS) {
      gSt[sp] = primsColor(op0, gListWalk ? primColor(op1.y) : opEmptyColor(i), maskBase, q, T);
      applyValueRule(prov, sp++);
    } else if (code == AM_OP_CONST) {
      gSt[sp++] = vec4(gListWalk ? ruleColor(prov) : opEmptyColor(i), uintBitsToFloat(op1.z));
    } else if (code == AM_OP_BEGINMAP) {
      if (!anyPrimActive(maskBase, op0.w, op0.y)) {
        gSt[sp] = vec4(gListWalk ? mapEmptyColor(op0.z) : opEmptyColor(i + op1.w), uintBitsToFloat(op1.z));
        i += op1.w;
        if (gListWalk) applyValueRule(POOLU(opBegin + i * AM_REC_OP + 1u).w, sp);  // its EndMap's rule
        ++sp;
        continue;
      }
      saved[level++] = q;
      q = mapToLocal(op1.y, q);
    } else if (code == AM_OP_ENDMAP) {
      q = saved[--level];
      applyValueRule(prov, sp - 1);
    } else {
      int n = int(op0.z);
      int base = sp - n;
      operatorColor(code, base, n, op1.x, T, prov);
      applyValueRule(prov, base);
      sp = base + 1;
    }
  }
  return sp > 0 ? gSt[0].xyz : gListWalk ? ruleColor(0u) : opEmptyColor(0u);
}

void colorPass() {
  gColorTable = P.colorPass.x;
  gAllPrimitives = pc.y != 0u;
  uint opBegin = gAllPrimitives ? pc.y : P.progA.x;
  gOpCount = gAllPrimitives ? pc.z : P.progA.y;
  uint opCount = gOpCount;
  float T = gAllPrimitives ? uintBitsToFloat(pc.w) : P.thresholds.x;
  uint total = min(control[AM_CTL_VERTICES], P.caps.x);
  // Dispatch k of four takes the k-th quarter of the vertex buffer, so a SIMD group's lanes hold
  // consecutive vertices: nearly always one block, so one region's list (with lists, each distinct
  // region among a group's lanes is one more walk for lavapipe's loop limiter).
  uint v = pc.x * gl_NumWorkGroups.x * AM_POLY_WG_NORMALS + gl_GlobalInvocationID.x;
  if (v >= total || gColorTable == 0u) return;
  vec4 q = positions[v];
  uint maskBase = floatBitsToUint(q.w);
  gListWalk = P.colorPass.z != 0u;
  if (gListWalk) {  // the vertex's region's list: regions of 2^shift blocks a side (regionOf's order)
    uint shift = P.colorPass.z - 1u;
    uvec3 dims = (P.gridBlocks.xyz + (1u << shift) - 1u) >> shift;
    uvec3 rc = blockCoord(maskBase / max(P.modes.y, 1u)) >> shift;
    uint region = rc.x + dims.x * (rc.y + dims.y * rc.z);
    uvec4 lists = POOLU((gAllPrimitives ? P.colorPass.w : P.regionLists.x) + region);
    opBegin = lists.x;
    opCount = lists.y;
  }
  vec3 c = clamp(programColor(opBegin, opCount, T, maskBase, q.xyz), 0.0, 1.0);
  uint bits = (packUnorm4x8(vec4(c, 0.0)) & 0x00ffffffu) | (AM_POLY_COLOR_TAG << 24);
  normals[v].w = uintBitsToFloat(bits);
}

void main() {
  colorPass();
  flagCutLoops(AM_OVERFLOW_CUT_COLORS);
}
