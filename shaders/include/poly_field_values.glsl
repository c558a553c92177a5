// Batched value interpreter of a packed FieldProgram (FieldEvaluator::runChunk,
// values only), FE_P points per invocation: each primitive's record is loaded
// once for all points. Included once per batch size with
//   FE_P         points per call
//   FE_PROGRAM   name of the one-program function
//   FE_COMBINED  name of the combined (single or morph) function
// Primitives whose bit is clear in the block mask contribute exactly 0 there
// (their bound does not reach the block), so skipping them is exact.

void FE_PROGRAM(uint opBegin, uint opCount, float T, uint maskBase, vec3 world[FE_P], out float result[FE_P]) {
  float st[AM_POLY_MAX_STACK * FE_P];
  vec3 saved[AM_POLY_MAX_MAP_DEPTH * FE_P];
  vec3 q[FE_P];
  for (int p = 0; p < FE_P; ++p) q[p] = world[p];
  int sp = 0, level = 0;
  for (uint i = 0u; i < opCount; ++i) {
    uint o = opBegin + i * AM_REC_OP;
    uvec4 op0 = POOLU(o);
    uint code = op0.x & 0xffu;
    if (code == AM_OP_PRIMS) {
      uint cls = (op0.x >> 8) & 0xffu;
      bool cmax = ((op0.x >> 16) & 1u) != 0u;
      float acc[FE_P];
      for (int p = 0; p < FE_P; ++p) acc[p] = 0.0;
      if (cls == AM_PRIM_CONVOLUTION) {
        for (uint k = 0u; k < op0.z; ++k) {
          if (!primActive(maskBase, op0.w + k)) continue;
          uint r = op0.y + k * AM_REC_CONV;
          vec4 r0 = POOLF(r), r1 = POOLF(r + 1u), r2 = POOLF(r + 2u);
          for (int p = 0; p < FE_P; ++p) acc[p] += convolutionValue(q[p], r0, r1, r2);
        }
      } else if (cls == AM_PRIM_SKELETAL) {
        for (uint k = 0u; k < op0.z; ++k) {
          if (!primActive(maskBase, op0.w + k)) continue;
          uint r = op0.y + k * AM_REC_SKEL;
          for (int p = 0; p < FE_P; ++p) {
            float v = skeletalValue(r, q[p]);
            acc[p] = cmax ? max(acc[p], v) : acc[p] + v;
          }
        }
      } else {
        for (uint k = 0u; k < op0.z; ++k) {
          if (!primActive(maskBase, op0.w + k)) continue;
          uint r = op0.y + k * AM_REC_CAPSULE;
          for (int p = 0; p < FE_P; ++p) {
            float v = capsuleValue(r, q[p], T);
            acc[p] = cmax ? max(acc[p], v) : acc[p] + v;
          }
        }
      }
      for (int p = 0; p < FE_P; ++p) st[sp * FE_P + p] = acc[p];
      ++sp;
    } else if (code == AM_OP_CONST) {
      float v = uintBitsToFloat(POOLU(o + 1u).z);
      for (int p = 0; p < FE_P; ++p) st[sp * FE_P + p] = v;
      ++sp;
    } else if (code == AM_OP_BEGINMAP) {
      uint m = POOLU(o + 1u).y;
      for (int p = 0; p < FE_P; ++p) {
        saved[level * FE_P + p] = q[p];
        q[p] = mapToLocal(m, q[p]);
      }
      ++level;
    } else if (code == AM_OP_ENDMAP) {
      --level;
      for (int p = 0; p < FE_P; ++p) q[p] = saved[level * FE_P + p];
    } else {
      int n = int(op0.z);
      int base = sp - n;
      uint prm = POOLU(o + 1u).x;
      for (int p = 0; p < FE_P; ++p) {
        float r = st[base * FE_P + p];
        if (code == AM_OP_SUM) {
          for (int k = 1; k < n; ++k) r += st[(base + k) * FE_P + p];
        } else if (code == AM_OP_MAX) {
          for (int k = 1; k < n; ++k) r = max(r, st[(base + k) * FE_P + p]);
        } else if (code == AM_OP_MIN) {
          for (int k = 1; k < n; ++k) r = min(r, st[(base + k) * FE_P + p]);
        } else if (code == AM_OP_HYPERBLEND) {
          float qq = paramAt(prm);
          float sum = 0.0;
          for (int k = 0; k < n; ++k) {
            float v = st[(base + k) * FE_P + p];
            sum += v > 0.0 ? pow(v, qq) : 0.0;
          }
          r = sum > 0.0 ? pow(sum, 1.0 / qq) : 0.0;
        } else if (code == AM_OP_DIFFERENCE) {
          r = min(r, 2.0 * T - st[(base + 1) * FE_P + p]);
        } else if (code == AM_OP_RUNION) {
          r = T + amRUnion(r - T, st[(base + 1) * FE_P + p] - T);
        } else if (code == AM_OP_RINTERSECTION) {
          r = T + amRIntersection(r - T, st[(base + 1) * FE_P + p] - T);
        } else if (code == AM_OP_BOUNDEDBLEND) {
          float s1 = r - T, s2 = st[(base + 1) * FE_P + p] - T, s3 = st[(base + 2) * FE_P + p] - T;
          r = T + amRUnion(s1, s2) +
              amBoundedDisplacement(s1, s2, s3, paramAt(prm), paramAt(prm + 1u), paramAt(prm + 2u), paramAt(prm + 3u));
        }
        st[base * FE_P + p] = r;
      }
      sp = base + 1;
    }
  }
  for (int p = 0; p < FE_P; ++p) result[p] = sp > 0 ? st[p] - T : -T;
}

// The field polygonised: program A alone, or the morph of A and B (morph_field.h).
void FE_COMBINED(uint maskBase, vec3 world[FE_P], out float result[FE_P]) {
  FE_PROGRAM(P.progA.x, P.progA.y, P.thresholds.x, maskBase, world, result);
  if (P.modes.x == AM_COMBINE_SINGLE) return;
  float b[FE_P];
  FE_PROGRAM(P.progB.x, P.progB.y, P.thresholds.y, maskBase, world, b);
  for (int p = 0; p < FE_P; ++p) {
    if (P.modes.x == AM_COMBINE_INTERPOLATE)
      result[p] = amMorphInterpolate(result[p], b[p], P.morph0.x);
    else
      result[p] = amMorphSpaceTime(result[p], b[p], P.morph0.y, P.morph0.z, P.morph0.w, P.morph1.x, P.morph1.y,
                                   P.morph1.z);
  }
}
