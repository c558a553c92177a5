// Value-and-gradient interpreter of a packed FieldProgram (FieldEvaluator::runChunk
// with gradients) at 4 points per invocation, for the emit pass's normals: one
// evaluation per vertex with the chain rule through every op, where the
// tetrahedral stencil takes four values. The CPU polygoniser's normals come from
// the same analytic gradients. Covers every op but HyperBlend, and affine maps
// (AM_ANALYTIC_GRADIENT); variants with either keep the stencil. Needs
// poly_field.glsl.

// Whether this variant's programs have analytic gradients here (one mask test: see poly_common.glsl).
#define AM_ANALYTIC_GRADIENT                                                                                  \
  (((kAmFeatures & AM_FEAT_OP_BIT(AM_OP_HYPERBLEND)) |                                                        \
    (kAmKinds & (AM_KIND_MAP_BIT(AM_MAP_TWIST) | AM_KIND_MAP_BIT(AM_MAP_TAPER) | AM_KIND_MAP_BIT(AM_MAP_BEND)))) == 0u)

// A value and its gradient at 4 points.
struct Grad4 {
  vec4 f, x, y, z;
};

Grad4 zeroGrad4(vec4 f) { return Grad4(f, vec4(0.0), vec4(0.0), vec4(0.0)); }

// convolution4 with its gradient (convolutionGradients), accumulated into g.
void convolutionGrad4(vec4 x, vec4 y, vec4 z, vec4 r0, vec4 r1, vec4 r2, inout Grad4 g) {
  ConvTerms c = convolutionTerms(x, y, z, r0, r1, r2);
  vec4 invD = c.Q * c.invDQ, invQ = c.D * c.invDQ;
  vec4 J0 = 0.25 * c.invP * (c.lu * invQ * invQ + c.u * invD * invD + 3.0 * c.F);
  vec4 radial = -4.0 * r2.x * r2.x * J0;
  vec4 axial = invD * invD - invQ * invQ;
  vec4 m = mix(vec4(0.0), vec4(r1.w), c.inCut);
  g.f += m * c.F;
  g.x += m * (radial * (c.dx - c.u * r1.x) + axial * r1.x);
  g.y += m * (radial * (c.dy - c.u * r1.y) + axial * r1.y);
  g.z += m * (radial * (c.dz - c.u * r1.z) + axial * r1.z);
}

// skeletalValue with its gradient (skeletalLoop).
float skeletalValueGrad(uint rec, vec3 q, out vec3 grad) {
  grad = vec3(0.0);
  if (outsideSkeletalCapsule(rec, q)) return 0.0;
  vec4 r3 = POOLF(rec + 3u);
  vec3 d = q - closestOnSkeleton(rec, q);
  float d2 = dot(d, d), R2 = r3.x * r3.x, I = r3.y, k = r3.z;
  if (!(d2 < R2) || R2 <= 0.0) return 0.0;
  float s = 1.0 - d2 / R2;
  float sk1 = k == 0.0 ? 0.0 : powStiffness(s, k - 1.0);
  grad = (-2.0 * I * k / R2 * sk1) * d;
  return k == 0.0 ? I : I * sk1 * s;
}

// capsuleValue with its gradient (capsuleLoop).
float capsuleValueGrad(uint rec, vec3 q, float T, out vec3 grad) {
  grad = vec3(0.0);
  vec4 r0 = POOLF(rec), r1 = POOLF(rec + 1u);
  if (r0.w <= 0.0) return 0.0;
  vec3 d = q - closestOnSegment(q, r0.xyz, r1.xyz);
  float dist = length(d);
  float v = T * (2.0 - dist * (1.0 / r0.w));
  if (v <= 0.0) return 0.0;
  if (dist > 0.0) grad = (-T / (r0.w * dist)) * d;
  return v;
}

// Partials of the R-functions (operators.h rUnion / rIntersection): sign +1 union, -1 intersection.
void rFunctionPartials(vec4 s1, vec4 s2, float sign, out vec4 r, out vec4 d1, out vec4 d2) {
  r = sqrt(s1 * s1 + s2 * s2);
  bvec4 pos = greaterThan(r, vec4(0.0));
  vec4 safe = mix(vec4(1.0), r, pos);
  d1 = mix(vec4(1.0), 1.0 + sign * s1 / safe, pos);
  d2 = mix(vec4(1.0), 1.0 + sign * s2 / safe, pos);
}

// Bounded blending (operators.h boundedBlend) of signed s1, s2 inside s3, with its partials d1..d3.
vec4 boundedBlendGrad(vec4 s1, vec4 s2, vec4 s3, float a0, float a1, float a2, float a3, out vec4 d1, out vec4 d2,
                      out vec4 d3) {
  vec4 r;
  rFunctionPartials(s1, s2, 1.0, r, d1, d2);
  vec4 u = s1 + s2 + r;
  vec4 r1 = (s1 / a1) * (s1 / a1) + (s2 / a2) * (s2 / a2);
  vec4 r2 = mix(vec4(0.0), (s3 / a3) * (s3 / a3), greaterThan(s3, vec4(0.0)));
  vec4 sum = r1 + r2;
  bvec4 inside = greaterThan(sum, vec4(0.0));
  vec4 rr = r1 / mix(vec4(1.0), sum, inside);
  inside = bvec4(vec4(inside) * vec4(lessThan(rr, vec4(1.0))));
  vec4 om = 1.0 - rr;
  vec4 disp = a0 * om * om * om / (1.0 + rr);
  vec4 dDisp = -a0 * om * om * (4.0 + 2.0 * rr) / ((1.0 + rr) * (1.0 + rr));
  vec4 inv = 1.0 / mix(vec4(1.0), sum * sum, inside);
  vec4 e1 = dDisp * (2.0 * s1 / (a1 * a1)) * r2 * inv;
  vec4 e2 = dDisp * (2.0 * s2 / (a2 * a2)) * r2 * inv;
  vec4 e3 = mix(vec4(0.0), dDisp * (-r1 * 2.0 * s3 / (a3 * a3)) * inv, greaterThan(s3, vec4(0.0)));
  d1 += mix(vec4(0.0), e1, inside);
  d2 += mix(vec4(0.0), e2, inside);
  d3 = mix(vec4(0.0), e3, inside);
  return u + mix(vec4(0.0), disp, inside);
}

Grad4 combineGrad(Grad4 a, vec4 da, Grad4 b, vec4 db, vec4 f) {
  return Grad4(f, da * a.x + db * b.x, da * a.y + db * b.y, da * a.z + db * b.z);
}

// f - T and its gradient, for one program at the points (x, y, z).
Grad4 programGrad(uint opBegin, uint opCount, float T, uint maskBase, vec4 px, vec4 py, vec4 pz) {
  Grad4 st[AM_POLY_MAX_STACK];
  vec4 saved[AM_POLY_MAX_MAP_DEPTH * 3];
  vec4 x = px, y = py, z = pz;
  int sp = 0, level = 0;
  Grad4 last = zeroGrad4(vec4(0.0));  // AM_STACKLESS: the only op's value
  for (uint i = 0u; i < opCount; ++i) {
    uint o = opBegin + i * AM_REC_OP;
    uvec4 op0 = POOLU(o);
    uint code = op0.x & 0xffu;
    if (AM_HAS_OP(AM_OP_PRIMS) && code == AM_OP_PRIMS) {
      uint cls = (op0.x >> 8) & 0xffu;
      bool cmax = ((op0.x >> 16) & 1u) != 0u;
      Grad4 a = zeroGrad4(vec4(0.0));
      if (AM_HAS_CLASS(AM_PRIM_CONVOLUTION) && cls == AM_PRIM_CONVOLUTION) {
        AM_FOR_BLOCK_CONVOLUTIONS(op0, maskBase, convolutionGrad4(x, y, z, POOLF(r), POOLF(r + 1u), POOLF(r + 2u), a);)
      } else if (AM_HAS_CLASS(AM_PRIM_SKELETAL) || AM_HAS_CLASS(AM_PRIM_CAPSULE)) {
        for (uint k = 0u; k < op0.z; ++k) {
          if (!primActive(maskBase, op0.w + k)) continue;
          bool skeletal = cls == AM_PRIM_SKELETAL;
          uint r = op0.y + k * (skeletal ? AM_REC_SKEL : AM_REC_CAPSULE);
          // The four points in one iteration (four copies of the kernel), in a loop whose trip count (1)
          // the compiler cannot see: lavapipe's loop limiter counts every iteration, and a loop per
          // point made 4 of a primitive's ~9 (see poly_field_program.glsl).
          for (uint h = 0u; h < P.caps.w; ++h) {
#define AM_GRAD_POINT(c)                                                            \
  {                                                                                 \
    vec3 q = vec3(x.c, y.c, z.c), grad = vec3(0.0);                                 \
    float v = 0.0;                                                                  \
    if (AM_HAS_CLASS(AM_PRIM_SKELETAL) && skeletal) v = skeletalValueGrad(r, q, grad); \
    if (AM_HAS_CLASS(AM_PRIM_CAPSULE) && !skeletal) v = capsuleValueGrad(r, q, T, grad); \
    bool replace = cmax && v > a.f.c;                                               \
    if (replace) {                                                                  \
      a.f.c = v;                                                                    \
      a.x.c = grad.x;                                                               \
      a.y.c = grad.y;                                                               \
      a.z.c = grad.z;                                                               \
    } else if (!cmax) {                                                             \
      a.f.c += v;                                                                   \
      a.x.c += grad.x;                                                              \
      a.y.c += grad.y;                                                              \
      a.z.c += grad.z;                                                              \
    }                                                                               \
  }
            AM_GRAD_POINT(x) AM_GRAD_POINT(y) AM_GRAD_POINT(z) AM_GRAD_POINT(w)
#undef AM_GRAD_POINT
          }
        }
      }
      if (AM_STACKLESS) {
        last = a;
      } else {
        st[sp] = a;
        ++sp;
      }
    } else if (AM_HAS_OP(AM_OP_CONST) && code == AM_OP_CONST) {
      st[sp] = zeroGrad4(vec4(uintBitsToFloat(POOLU(o + 1u).z)));
      ++sp;
    } else if (AM_HAS_OP(AM_OP_BEGINMAP) && code == AM_OP_BEGINMAP) {
      uvec4 op1 = POOLU(o + 1u);
      if (!anyPrimActive(maskBase, op0.w, op0.y)) {  // the subtree is constant here (gpu_field_program.cpp)
        st[sp] = zeroGrad4(vec4(uintBitsToFloat(op1.z)));
        ++sp;
        i += op1.w;
        continue;
      }
      uint m = op1.y;
      vec4 r0 = POOLF(m), r1 = POOLF(m + 1u), r2 = POOLF(m + 2u), r3 = POOLF(m + 3u);
      saved[3 * level] = x;
      saved[3 * level + 1] = y;
      saved[3 * level + 2] = z;
      vec4 dx = x - r3.x, dy = y - r3.y, dz = z - r3.z;  // affine: L (x - origin), L's columns r0..r2
      x = r0.x * dx + r1.x * dy + r2.x * dz;
      y = r0.y * dx + r1.y * dy + r2.y * dz;
      z = r0.z * dx + r1.z * dy + r2.z * dz;
      ++level;
    } else if (AM_HAS_OP(AM_OP_ENDMAP) && code == AM_OP_ENDMAP) {
      --level;
      x = saved[3 * level];
      y = saved[3 * level + 1];
      z = saved[3 * level + 2];
      uint m = POOLU(o + 1u).y;
      vec4 r0 = POOLF(m), r1 = POOLF(m + 1u), r2 = POOLF(m + 2u);
      Grad4 g = st[sp - 1];  // grad_world = L^T grad_local
      st[sp - 1] = Grad4(g.f, r0.x * g.x + r0.y * g.y + r0.z * g.z, r1.x * g.x + r1.y * g.y + r1.z * g.z,
                         r2.x * g.x + r2.y * g.y + r2.z * g.z);
    } else if (AM_HAS_OPERATORS) {
      int n = int(op0.z);
      int base = sp - n;
      uint prm = POOLU(o + 1u).x;
      Grad4 r = st[base];
      if (AM_HAS_OP(AM_OP_SUM) && code == AM_OP_SUM) {
        for (int k = 1; k < n; ++k) {
          Grad4 b = st[base + k];
          r = Grad4(r.f + b.f, r.x + b.x, r.y + b.y, r.z + b.z);
        }
      } else if ((AM_HAS_OP(AM_OP_MAX) && code == AM_OP_MAX) || (AM_HAS_OP(AM_OP_MIN) && code == AM_OP_MIN)) {
        bool mx = code == AM_OP_MAX;
        for (int k = 1; k < n; ++k) {
          Grad4 b = st[base + k];
          vec4 take = vec4(mx ? greaterThan(b.f, r.f) : lessThan(b.f, r.f));
          r = Grad4(mix(r.f, b.f, take), mix(r.x, b.x, take), mix(r.y, b.y, take), mix(r.z, b.z, take));
        }
      } else if (AM_HAS_OP(AM_OP_DIFFERENCE) && code == AM_OP_DIFFERENCE) {
        Grad4 b = st[base + 1];
        vec4 other = 2.0 * T - b.f;
        vec4 take = vec4(lessThan(other, r.f));
        r = Grad4(mix(r.f, other, take), mix(r.x, -b.x, take), mix(r.y, -b.y, take), mix(r.z, -b.z, take));
      } else if ((AM_HAS_OP(AM_OP_RUNION) && code == AM_OP_RUNION) ||
                 (AM_HAS_OP(AM_OP_RINTERSECTION) && code == AM_OP_RINTERSECTION)) {
        float sign = code == AM_OP_RUNION ? 1.0 : -1.0;
        Grad4 b = st[base + 1];
        vec4 s1 = r.f - T, s2 = b.f - T, q, d1, d2;
        rFunctionPartials(s1, s2, sign, q, d1, d2);
        r = combineGrad(r, d1, b, d2, T + s1 + s2 + sign * q);
      } else if (AM_HAS_OP(AM_OP_BOUNDEDBLEND) && code == AM_OP_BOUNDEDBLEND) {
        Grad4 b = st[base + 1], c = st[base + 2];
        vec4 d1, d2, d3;
        vec4 v = boundedBlendGrad(r.f - T, b.f - T, c.f - T, paramAt(prm), paramAt(prm + 1u), paramAt(prm + 2u),
                                  paramAt(prm + 3u), d1, d2, d3);
        Grad4 ab = combineGrad(r, d1, b, d2, T + v);
        r = Grad4(ab.f, ab.x + d3 * c.x, ab.y + d3 * c.y, ab.z + d3 * c.z);
      } else if (AM_HAS_OP(AM_OP_REMAP) && code == AM_OP_REMAP) {
        float sc = paramAt(prm), k = paramAt(prm + 1u);
        vec4 d = vec4(amRemapSlope(r.f.x, sc, k, T), amRemapSlope(r.f.y, sc, k, T), amRemapSlope(r.f.z, sc, k, T),
                      amRemapSlope(r.f.w, sc, k, T));
        r = Grad4(amRemap4(r.f, sc, k, T), d * r.x, d * r.y, d * r.z);
      }
      st[base] = r;
      sp = base + 1;
    }
  }
  Grad4 res = AM_STACKLESS ? last : (sp > 0 ? st[0] : zeroGrad4(vec4(0.0)));
  res.f -= T;
  return res;
}

// The polygonised field and its gradient at the points (fieldV's combination).
Grad4 fieldGrad(uint maskBase, vec4 x, vec4 y, vec4 z) {
  Grad4 a = programGrad(gOps.x, gOps.y, P.thresholds.x, maskBase, x, y, z);
  if (AM_SINGLE_ONLY) return a;
  if (P.modes.x == AM_COMBINE_SINGLE) return a;
  Grad4 b = programGrad(gOps.z, gOps.w, P.thresholds.y, maskBase, x, y, z);
  if (AM_HAS_COMBINE(AM_COMBINE_INTERPOLATE) && P.modes.x == AM_COMBINE_INTERPOLATE) {
    float w = P.morph0.x;
    return combineGrad(a, vec4(1.0 - w), b, vec4(w), (1.0 - w) * a.f + w * b.f);
  }
  // Space-time blending (morph_field.h): m = B(g1, g2, bound), g1 = f1 ^ (-tau), g2 = f2 ^ tau1.
  float tau = P.morph0.z * P.morph0.y, tau1 = P.morph0.z * (P.morph0.y - 1.0);
  vec4 q1, e1, unused1, q2, e2, unused2;
  rFunctionPartials(a.f, vec4(-tau), -1.0, q1, e1, unused1);
  rFunctionPartials(b.f, vec4(tau1), -1.0, q2, e2, unused2);
  vec4 g1 = a.f - tau - q1, g2 = b.f + tau1 - q2;
  float bound = amRIntersection(tau, -tau1);
  vec4 d1, d2, d3;
  vec4 m = boundedBlendGrad(g1, g2, vec4(bound), P.morph0.w, P.morph1.x, P.morph1.y, P.morph1.z, d1, d2, d3);
  return combineGrad(a, d1 * e1, b, d2 * e2, m);
}
