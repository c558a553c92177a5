// Batched value interpreter of a packed FieldProgram (FieldEvaluator::runChunk,
// values only) at 8 points per invocation, held as two vec4 per coordinate: a
// primitive's record is loaded once for all 8 points, and nothing in the
// primitive loops indexes a local array (slow on lavapipe). Primitives whose bit
// is clear in the block mask contribute exactly 0 there (their bound does not
// reach the block), so skipping them is exact. Needs poly_field.glsl.

struct Points8 {
  vec4 x0, x1, y0, y1, z0, z1;  // points 0..3 and 4..7
};

vec4 rUnion4(vec4 s1, vec4 s2) { return s1 + s2 + sqrt(s1 * s1 + s2 * s2); }
vec4 rIntersection4(vec4 s1, vec4 s2) { return s1 + s2 - sqrt(s1 * s1 + s2 * s2); }

vec4 boundedDisplacement4(vec4 s1, vec4 s2, vec4 s3, float a0, float a1, float a2, float a3) {
  return vec4(amBoundedDisplacement(s1.x, s2.x, s3.x, a0, a1, a2, a3),
              amBoundedDisplacement(s1.y, s2.y, s3.y, a0, a1, a2, a3),
              amBoundedDisplacement(s1.z, s2.z, s3.z, a0, a1, a2, a3),
              amBoundedDisplacement(s1.w, s2.w, s3.w, a0, a1, a2, a3));
}

// f = p - T of one program at the 8 points: out0 for points 0..3, out1 for 4..7.
void program8(uint opBegin, uint opCount, float T, uint maskBase, Points8 w, out vec4 out0, out vec4 out1) {
  vec4 st[AM_POLY_MAX_STACK * 2];
  vec4 saved[AM_POLY_MAX_MAP_DEPTH * 6];
  vec4 x0 = w.x0, x1 = w.x1, y0 = w.y0, y1 = w.y1, z0 = w.z0, z1 = w.z1;
  int sp = 0, level = 0;
  for (uint i = 0u; i < opCount; ++i) {
    uint o = opBegin + i * AM_REC_OP;
    uvec4 op0 = POOLU(o);
    uint code = op0.x & 0xffu;
    if (code == AM_OP_PRIMS) {
      uint cls = (op0.x >> 8) & 0xffu;
      bool cmax = ((op0.x >> 16) & 1u) != 0u;
      vec4 a0 = vec4(0.0), a1 = vec4(0.0);
      if (cls == AM_PRIM_CONVOLUTION) {
        for (uint k = 0u; k < op0.z; ++k) {
          if (!primActive(maskBase, op0.w + k)) continue;
          uint r = op0.y + k * AM_REC_CONV;
          vec4 r0 = POOLF(r), r1 = POOLF(r + 1u), r2 = POOLF(r + 2u);
          a0 += convolution4(x0, y0, z0, r0, r1, r2);
          a1 += convolution4(x1, y1, z1, r0, r1, r2);
        }
      } else {
        // Skeletal and capsule kernels are long (closest points on nine skeleton
        // kinds): one copy in a loop whose trip count the compiler cannot see
        // (P.caps.w = 8), rather than eight inlined copies.
        for (uint k = 0u; k < op0.z; ++k) {
          if (!primActive(maskBase, op0.w + k)) continue;
          bool skeletal = cls == AM_PRIM_SKELETAL;
          uint r = op0.y + k * (skeletal ? AM_REC_SKEL : AM_REC_CAPSULE);
          for (uint p = 0u; p < P.caps.w; ++p) {
            uint c = p & 3u;
            vec3 q = p < 4u ? vec3(x0[c], y0[c], z0[c]) : vec3(x1[c], y1[c], z1[c]);
            float v = skeletal ? skeletalValue(r, q) : capsuleValue(r, q, T);
            if (p < 4u) a0[c] = cmax ? max(a0[c], v) : a0[c] + v;
            else a1[c] = cmax ? max(a1[c], v) : a1[c] + v;
          }
        }
      }
      st[2 * sp] = a0;
      st[2 * sp + 1] = a1;
      ++sp;
    } else if (code == AM_OP_CONST) {
      float v = uintBitsToFloat(POOLU(o + 1u).z);
      st[2 * sp] = vec4(v);
      st[2 * sp + 1] = vec4(v);
      ++sp;
    } else if (code == AM_OP_BEGINMAP) {
      uint m = POOLU(o + 1u).y;
      int s = 6 * level;
      saved[s] = x0;
      saved[s + 1] = x1;
      saved[s + 2] = y0;
      saved[s + 3] = y1;
      saved[s + 4] = z0;
      saved[s + 5] = z1;
      for (uint p = 0u; p < P.caps.w; ++p) {  // one copy of the map code (see above)
        uint c = p & 3u;
        vec3 q = mapToLocal(m, p < 4u ? vec3(x0[c], y0[c], z0[c]) : vec3(x1[c], y1[c], z1[c]));
        if (p < 4u) {
          x0[c] = q.x;
          y0[c] = q.y;
          z0[c] = q.z;
        } else {
          x1[c] = q.x;
          y1[c] = q.y;
          z1[c] = q.z;
        }
      }
      ++level;
    } else if (code == AM_OP_ENDMAP) {
      --level;
      int s = 6 * level;
      x0 = saved[s];
      x1 = saved[s + 1];
      y0 = saved[s + 2];
      y1 = saved[s + 3];
      z0 = saved[s + 4];
      z1 = saved[s + 5];
    } else {
      int n = int(op0.z);
      int base = sp - n;
      uint prm = POOLU(o + 1u).x;
      for (int h = 0; h < 2; ++h) {
        vec4 r = st[2 * base + h];
        if (code == AM_OP_SUM) {
          for (int k = 1; k < n; ++k) r += st[2 * (base + k) + h];
        } else if (code == AM_OP_MAX) {
          for (int k = 1; k < n; ++k) r = max(r, st[2 * (base + k) + h]);
        } else if (code == AM_OP_MIN) {
          for (int k = 1; k < n; ++k) r = min(r, st[2 * (base + k) + h]);
        } else if (code == AM_OP_HYPERBLEND) {
          float q = paramAt(prm);
          vec4 sum = vec4(0.0);
          for (int k = 0; k < n; ++k) {
            vec4 v = st[2 * (base + k) + h];
            sum += mix(vec4(0.0), pow(max(v, vec4(0.0)), vec4(q)), greaterThan(v, vec4(0.0)));
          }
          r = mix(vec4(0.0), pow(sum, vec4(1.0 / q)), greaterThan(sum, vec4(0.0)));
        } else if (code == AM_OP_DIFFERENCE) {
          r = min(r, 2.0 * T - st[2 * (base + 1) + h]);
        } else if (code == AM_OP_RUNION) {
          r = T + rUnion4(r - T, st[2 * (base + 1) + h] - T);
        } else if (code == AM_OP_RINTERSECTION) {
          r = T + rIntersection4(r - T, st[2 * (base + 1) + h] - T);
        } else if (code == AM_OP_BOUNDEDBLEND) {
          vec4 s1 = r - T, s2 = st[2 * (base + 1) + h] - T, s3 = st[2 * (base + 2) + h] - T;
          r = T + rUnion4(s1, s2) +
              boundedDisplacement4(s1, s2, s3, paramAt(prm), paramAt(prm + 1u), paramAt(prm + 2u), paramAt(prm + 3u));
        }
        st[2 * base + h] = r;
      }
      sp = base + 1;
    }
  }
  out0 = sp > 0 ? st[0] - T : vec4(-T);
  out1 = sp > 0 ? st[1] - T : vec4(-T);
}

vec4 spaceTime4(vec4 f1, vec4 f2) {
  vec4 r;
  for (int c = 0; c < 4; ++c)
    r[c] = amMorphSpaceTime(f1[c], f2[c], P.morph0.y, P.morph0.z, P.morph0.w, P.morph1.x, P.morph1.y, P.morph1.z);
  return r;
}

// The field polygonised at the 8 points: program A alone, or the morph of A and B (morph_field.h).
void field8(uint maskBase, Points8 w, out vec4 out0, out vec4 out1) {
  program8(P.progA.x, P.progA.y, P.thresholds.x, maskBase, w, out0, out1);
  if (P.modes.x == AM_COMBINE_SINGLE) return;
  vec4 b0, b1;
  program8(P.progB.x, P.progB.y, P.thresholds.y, maskBase, w, b0, b1);
  if (P.modes.x == AM_COMBINE_INTERPOLATE) {
    float wt = P.morph0.x;
    out0 = (1.0 - wt) * out0 + wt * b0;
    out1 = (1.0 - wt) * out1 + wt * b1;
  } else {
    out0 = spaceTime4(out0, b0);
    out1 = spaceTime4(out1, b1);
  }
}

Points8 points8(vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec3 p4, vec3 p5, vec3 p6, vec3 p7) {
  Points8 w;
  w.x0 = vec4(p0.x, p1.x, p2.x, p3.x);
  w.y0 = vec4(p0.y, p1.y, p2.y, p3.y);
  w.z0 = vec4(p0.z, p1.z, p2.z, p3.z);
  w.x1 = vec4(p4.x, p5.x, p6.x, p7.x);
  w.y1 = vec4(p4.y, p5.y, p6.y, p7.y);
  w.z1 = vec4(p4.z, p5.z, p6.z, p7.z);
  return w;
}
