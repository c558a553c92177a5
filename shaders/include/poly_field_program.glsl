// The batched value interpreter (programV / fieldV), instantiated by
// poly_field_batch.glsl for two point layouts. AM_LINES 0: any points
// (PointsV). AM_LINES 1: groups of 4 points along a grid line (PointsL: the two
// constant coordinates one float per group), for programs without maps whose
// primitives are convolution segments; the kernel then takes the constant
// coordinates' terms once per group, with the same operations in an order that
// gives the same values bit for bit (convolutionLine4).
// Names: AM_POINTS, AM_PROGRAM, AM_FIELD; AM_YZ: the type of y and z per group.

// f = p - T of one program at the invocation's points.
void AM_PROGRAM(uint opBegin, uint opCount, float T, uint maskBase, AM_POINTS w, out vec4 res[AM_FIELD_V]) {
  vec4 st[AM_POLY_MAX_STACK * AM_FIELD_V];
#if !AM_LINES
  vec4 saved[AM_POLY_MAX_MAP_DEPTH * 3 * AM_FIELD_V];
#endif
  vec4 x[AM_FIELD_V] = w.x;
  AM_YZ y[AM_FIELD_V] = w.y, z[AM_FIELD_V] = w.z;
#if AM_LINES
  uint axis[AM_FIELD_V] = w.axis;
#endif
  const int V = AM_FIELD_V;
  int sp = 0, level = 0;
  vec4 last[AM_FIELD_V];  // AM_STACKLESS: the value of the program's only op
#define AM_NONE(j) last[j] = vec4(-T);
  AM_EACH(AM_NONE)
  for (uint i = 0u; i < opCount; ++i) {
    uint o = opBegin + i * AM_REC_OP;
    uvec4 op0 = POOLU(o);
    uint code = op0.x & 0xffu;
    if (AM_HAS_OP(AM_OP_PRIMS) && code == AM_OP_PRIMS) {
      uint cls = (op0.x >> 8) & 0xffu;
      bool cmax = ((op0.x >> 16) & 1u) != 0u;
      vec4 a[AM_FIELD_V];
#define AM_ZERO(j) a[j] = vec4(0.0);
      AM_EACH(AM_ZERO)
      if (AM_HAS_CLASS(AM_PRIM_CONVOLUTION) && cls == AM_PRIM_CONVOLUTION) {
#if AM_LINES
#define AM_CONV(j) a[j] += convolutionLine4(x[j], y[j], z[j], axis[j], r0, r1, r2);
#else
#define AM_CONV(j) a[j] += convolution4(x[j], y[j], z[j], r0, r1, r2);
#endif
        AM_FOR_BLOCK_CONVOLUTIONS(op0, maskBase, vec4 r0 = POOLF(r); vec4 r1 = POOLF(r + 1u);
                                  vec4 r2 = POOLF(r + 2u); AM_EACH(AM_CONV))
#if !AM_LINES
      } else if (AM_HAS_CLASS(AM_PRIM_SKELETAL) || AM_HAS_CLASS(AM_PRIM_CAPSULE)) {
        // Skeletal and capsule kernels are long (closest points on nine skeleton
        // kinds): four copies (one vec4 of points) in a loop over the V vec4 whose
        // trip count the compiler cannot see (P.caps.w = 1), rather than 4 V inlined
        // copies. Four points per iteration rather than one: lavapipe's loop limiter
        // counts every iteration, and the per-point loop was 8 of a primitive's ~14
        // (docs/gpu-polygonizer.md, "Lavapipe findings").
        for (uint k = 0u; k < op0.z; ++k) {
          if (!primActive(maskBase, op0.w + k)) continue;
          bool skeletal = cls == AM_PRIM_SKELETAL;
          uint r = op0.y + k * (skeletal ? AM_REC_SKEL : AM_REC_CAPSULE);
          for (uint h = 0u; h < uint(V) * P.caps.w; ++h) {
            bool hi = h >= 1u;  // second vec4 (V = 2); the arrays are only indexed by constants
            vec4 px = hi ? x[V - 1] : x[0], py = hi ? y[V - 1] : y[0], pz = hi ? z[V - 1] : z[0];
            vec4 v = vec4(0.0);
            if (AM_HAS_CLASS(AM_PRIM_SKELETAL) && skeletal)
              v = vec4(skeletalValue(r, vec3(px.x, py.x, pz.x)), skeletalValue(r, vec3(px.y, py.y, pz.y)),
                       skeletalValue(r, vec3(px.z, py.z, pz.z)), skeletalValue(r, vec3(px.w, py.w, pz.w)));
            if (AM_HAS_CLASS(AM_PRIM_CAPSULE) && !skeletal)
              v = vec4(capsuleValue(r, vec3(px.x, py.x, pz.x), T), capsuleValue(r, vec3(px.y, py.y, pz.y), T),
                       capsuleValue(r, vec3(px.z, py.z, pz.z), T), capsuleValue(r, vec3(px.w, py.w, pz.w), T));
            vec4 acc = hi ? a[V - 1] : a[0];
            acc = cmax ? max(acc, v) : acc + v;
            if (hi) a[V - 1] = acc;
            else a[0] = acc;
          }
        }
#endif
      }
      if (AM_STACKLESS) {
#define AM_LAST(j) last[j] = a[j] - T;
        AM_EACH(AM_LAST)
      } else {
#define AM_PUSH(j) st[V * sp + j] = a[j];
        AM_EACH(AM_PUSH)
        ++sp;
      }
    } else if (AM_HAS_OP(AM_OP_CONST) && code == AM_OP_CONST) {
      float v = uintBitsToFloat(POOLU(o + 1u).z);
      for (int h = 0; h < V; ++h) st[V * sp + h] = vec4(v);
      ++sp;
#if !AM_LINES
    } else if (AM_HAS_OP(AM_OP_BEGINMAP) && code == AM_OP_BEGINMAP) {
      uvec4 op1 = POOLU(o + 1u);
      if (!anyPrimActive(maskBase, op0.w, op0.y)) {
        // No primitive of the subtree this map opens reaches the block: its value is constant
        // (as FieldProgram::specialise on the CPU). Push it and go on after the subtree.
        for (int h = 0; h < V; ++h) st[V * sp + h] = vec4(uintBitsToFloat(op1.z));
        ++sp;
        i += op1.w;
        continue;
      }
      uint m = op1.y;
      int s = 3 * V * level;
#define AM_SAVE(j) saved[s + j] = x[j]; saved[s + V + j] = y[j]; saved[s + 2 * V + j] = z[j];
      AM_EACH(AM_SAVE)
      if (AM_AFFINE_MAPS_ONLY) {
        // Affine maps only (frames): L (x - o) on whole vec4s of points, as mapToLocal computes it
        // per point. On lavapipe the per-point loop below, with its run-time component indices,
        // cost more than the primitives of a frame-heavy BlobTree.
        vec4 r0 = POOLF(m), r1 = POOLF(m + 1u), r2 = POOLF(m + 2u), r3 = POOLF(m + 3u);
#define AM_AFFINE(j)                                                                        \
  {                                                                                         \
    vec4 dx = x[j] - r3.x, dy = y[j] - r3.y, dz = z[j] - r3.z;                              \
    x[j] = r0.x * dx + r1.x * dy + r2.x * dz;                                               \
    y[j] = r0.y * dx + r1.y * dy + r2.y * dz;                                               \
    z[j] = r0.z * dx + r1.z * dy + r2.z * dz;                                               \
  }
        AM_EACH(AM_AFFINE)
      } else
      for (uint p = 0u; p < 4u * uint(V) * P.caps.w; ++p) {  // one copy of the map code (see above)
        bool hi = p >= 4u;
        uint c = p & 3u;
        vec4 px = hi ? x[V - 1] : x[0], py = hi ? y[V - 1] : y[0], pz = hi ? z[V - 1] : z[0];
        vec3 q = mapToLocal(m, vec3(px[c], py[c], pz[c]));
        px[c] = q.x;
        py[c] = q.y;
        pz[c] = q.z;
        if (hi) {
          x[V - 1] = px;
          y[V - 1] = py;
          z[V - 1] = pz;
        } else {
          x[0] = px;
          y[0] = py;
          z[0] = pz;
        }
      }
      ++level;
    } else if (AM_HAS_OP(AM_OP_ENDMAP) && code == AM_OP_ENDMAP) {
      --level;
      int s = 3 * V * level;
#define AM_RESTORE(j) x[j] = saved[s + j]; y[j] = saved[s + V + j]; z[j] = saved[s + 2 * V + j];
      AM_EACH(AM_RESTORE)
#endif
    } else if (AM_HAS_OPERATORS) {
      int n = int(op0.z);
      int base = sp - n;
      uint prm = POOLU(o + 1u).x;
      for (int h = 0; h < V; ++h) {
        vec4 r = st[V * base + h];
        if (AM_HAS_OP(AM_OP_SUM) && code == AM_OP_SUM) {
          for (int k = 1; k < n; ++k) r += st[V * (base + k) + h];
        } else if (AM_HAS_OP(AM_OP_MAX) && code == AM_OP_MAX) {
          for (int k = 1; k < n; ++k) r = max(r, st[V * (base + k) + h]);
        } else if (AM_HAS_OP(AM_OP_MIN) && code == AM_OP_MIN) {
          for (int k = 1; k < n; ++k) r = min(r, st[V * (base + k) + h]);
        } else if (AM_HAS_OP(AM_OP_HYPERBLEND) && code == AM_OP_HYPERBLEND) {
          float q = paramAt(prm);
          vec4 sum = vec4(0.0);
          for (int k = 0; k < n; ++k) {
            vec4 v = st[V * (base + k) + h];
            sum += mix(vec4(0.0), pow(max(v, vec4(0.0)), vec4(q)), greaterThan(v, vec4(0.0)));
          }
          r = mix(vec4(0.0), pow(sum, vec4(1.0 / q)), greaterThan(sum, vec4(0.0)));
        } else if (AM_HAS_OP(AM_OP_DIFFERENCE) && code == AM_OP_DIFFERENCE) {
          r = min(r, 2.0 * T - st[V * (base + 1) + h]);
        } else if (AM_HAS_OP(AM_OP_RUNION) && code == AM_OP_RUNION) {
          r = T + rUnion4(r - T, st[V * (base + 1) + h] - T);
        } else if (AM_HAS_OP(AM_OP_RINTERSECTION) && code == AM_OP_RINTERSECTION) {
          r = T + rIntersection4(r - T, st[V * (base + 1) + h] - T);
        } else if (AM_HAS_OP(AM_OP_BOUNDEDBLEND) && code == AM_OP_BOUNDEDBLEND) {
          vec4 s1 = r - T, s2 = st[V * (base + 1) + h] - T, s3 = st[V * (base + 2) + h] - T;
          r = T + rUnion4(s1, s2) +
              boundedDisplacement4(s1, s2, s3, paramAt(prm), paramAt(prm + 1u), paramAt(prm + 2u), paramAt(prm + 3u));
        } else if (AM_HAS_OP(AM_OP_REMAP) && code == AM_OP_REMAP) {
          r = amRemap4(r, paramAt(prm), paramAt(prm + 1u), T);
        }
        st[V * base + h] = r;
      }
      sp = base + 1;
    }
  }
  if (AM_STACKLESS) {
    res = last;
    return;
  }
#define AM_RESULT(j) res[j] = sp > 0 ? st[j] - T : vec4(-T);
  AM_EACH(AM_RESULT)
}

// The field polygonised at the invocation's points: program A alone, or the
// morph of A and B (morph_field.h).
void AM_FIELD(uint maskBase, AM_POINTS w, out vec4 res[AM_FIELD_V]) {
  AM_PROGRAM(gOps.x, gOps.y, P.thresholds.x, maskBase, w, res);
  if (AM_SINGLE_ONLY) return;
  if (P.modes.x == AM_COMBINE_SINGLE) return;
  vec4 b[AM_FIELD_V];
  AM_PROGRAM(gOps.z, gOps.w, P.thresholds.y, maskBase, w, b);
  if (AM_HAS_COMBINE(AM_COMBINE_INTERPOLATE) && P.modes.x == AM_COMBINE_INTERPOLATE) {
    float wt = P.morph0.x;
#define AM_LERP(j) res[j] = (1.0 - wt) * res[j] + wt * b[j];
    AM_EACH(AM_LERP)
  } else if (AM_HAS_COMBINE(AM_COMBINE_SPACETIME)) {
#define AM_SPACETIME(j) res[j] = spaceTime4(res[j], b[j]);
    AM_EACH(AM_SPACETIME)
  }
}


#undef AM_AFFINE
#undef AM_CONV
#undef AM_LAST
#undef AM_LERP
#undef AM_NONE
#undef AM_PUSH
#undef AM_RESTORE
#undef AM_RESULT
#undef AM_SAVE
#undef AM_SPACETIME
#undef AM_ZERO
