// The transition of a skinned mesh onto / from its stand-in (docs/design.md §4),
// the GPU twin of engine/core/standin_morph/transition.cpp (evaluateTransition,
// transitionAlphas) and standin/project_onto_standin.cpp (re-projection):
//   p' = sum_j w_j M_j lerp(p, p + dp, alpha),  n' = (model skin)^-T nlerp(n, n~, alpha)
// with alpha from the easing table and the weight map, and above
// reprojectFrom Newton steps onto the posed stand-in field, blended in by
// smoothstep (fully at alpha = 1, so alpha = 1 lies on that frame's surface).
// Needs joints[] and pc (mesh_push.glsl), skinning.glsl and
// transition_constants.h first. At alpha = 0 this is mesh.vert's skinning,
// operation for operation.

// Per-draw parameters (C++ mirror: TransitionParams in engine/gpu/transition/transition_params.h).
layout(set = AM_TRANSITION_SET, binding = AM_TRANSITION_BINDING_PARAMS, std430) readonly buffer TransitionParams {
  vec4 alphaParams;   // x: alpha of every vertex (no weight map), y: progress u, z: shift, w: duration
  vec4 reprojParams;  // x: reprojectFrom, y: tolerance, z: longest Newton step (m), w: threshold T
  uvec4 mode;         // x: AM_TR_* flags, y: primitives, z: segments, w: Newton iterations
  vec4 reserved;
  vec4 lut[AM_TRANSITION_LUT_VEC4];                 // easing table, 4 per vec4
  vec4 prims[3 * AM_TRANSITION_MAX_SEGMENTS];       // TransitionPrimitive records
  vec4 segs[2 * AM_TRANSITION_MAX_SEGMENTS];        // posed segments: (a, radius), (b, 0)
} tr;

float amEasingTable(int k) { return tr.lut[k >> 2][k & 3]; }

// transitionAlphas for one vertex with weight-map value m.
float amTransitionAlpha(float m) {
  uint flags = tr.mode.x;
  if ((flags & AM_TR_PER_VERTEX) == 0u) return tr.alphaParams.x;
  float uc = tr.alphaParams.y, s = tr.alphaParams.z, dur = tr.alphaParams.w;
  float mm = clamp(m, 0.0, 1.0);
  float x = clamp((uc - s * (1.0 - mm)) / dur, 0.0, 1.0) * float(AM_TRANSITION_LUT_FLOATS - 1);
  int k = min(AM_TRANSITION_LUT_FLOATS - 2, int(x));
  float l0 = amEasingTable(k), l1 = amEasingTable(k + 1);
  float a = l0 + (l1 - l0) * (x - float(k));
  return (flags & AM_TR_EXPAND) != 0u ? 1.0 - a : a;
}

// atan2(y, x) for y > 0: the Cephes polynomial of field_kernels.cpp.
float amAtan2PositiveY(float y, float x) {
  float ax = abs(x);
  float mn = min(ax, y), mx = max(ax, y);
  bool big = mn > 0.41421356237 * mx;
  float t = (big ? mn - mx : mn) / (big ? mn + mx : mx);
  float z = t * t;
  float r = (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z - 3.33329491539e-1) * z * t + t;
  r += big ? 0.78539816340 : 0.0;
  r = y > ax ? 1.57079632679 - r : r;
  r = x < 0.0 ? 3.14159265359 - r : r;
  return r;
}

vec3 amClosestOnSegment(vec3 x, vec3 a, vec3 b) {
  vec3 ab = b - a;
  float l2 = dot(ab, ab);
  if (l2 <= 0.0) return a;
  return a + clamp(dot(x - a, ab) / l2, 0.0, 1.0) * ab;
}

float amPowStiffness(float base, float k) {
  int ki = int(k);
  if (float(ki) == k && ki >= 0 && ki <= 8) {
    float r = 1.0;
    for (int i = 0; i < ki; ++i) r *= base;
    return r;
  }
  return pow(base, k);
}

// The posed stand-in field f = sum - T (>= 0 inside) and its gradient
// (convolutionGradients / skeletalLoop of field_kernels.cpp).
float amStandinField(vec3 x, out vec3 grad) {
  uint flags = tr.mode.x;
  bool capsules = (flags & AM_TR_CAPSULES) != 0u, useMax = (flags & AM_TR_COMBINE_MAX) != 0u;
  float f = 0.0;
  vec3 g = vec3(0.0);
  for (uint i = 0u; i < tr.mode.y; ++i) {
    vec4 r0 = tr.prims[3u * i], r1 = tr.prims[3u * i + 1u], r2 = tr.prims[3u * i + 2u];
    if (!capsules) {
      vec3 d = x - r0.xyz, ax = r1.xyz;
      float l = r0.w, w = r1.w, S = r2.x, S2 = S * S, cut2 = r2.y;
      float dd = dot(d, d), u = dot(d, ax);
      float perp2 = max(dd - u * u, 0.0);
      float P = 1.0 + S2 * perp2, D = 1.0 + S2 * dd, lu = l - u;
      float e2 = dd - 2.0 * l * u + l * l;
      float Q = 1.0 + S2 * e2;
      float invP = 1.0 / P, p = sqrt(P);
      float A = amAtan2PositiveY(S * l * p, P - S2 * u * lu);
      float invDQ = 1.0 / (D * Q), invD = Q * invDQ, invQ = D * invDQ;
      float F = 0.5 * invP * ((u * Q + lu * D) * invDQ + A * p * invP * (1.0 / S));
      float J0 = 0.25 * invP * (lu * invQ * invQ + u * invD * invD + 3.0 * F);
      float radial = -4.0 * S2 * J0, axial = invD * invD - invQ * invQ;
      float seg2 = u < 0.0 ? dd : (u > l ? e2 : perp2);
      float m = seg2 <= cut2 ? w : 0.0;
      f += m * F;
      g += m * (radial * (d - u * ax) + axial * ax);
    } else {
      vec3 d = x - amClosestOnSegment(x, r0.xyz, r1.xyz);
      float d2 = dot(d, d), R2 = r0.w * r0.w, I = r1.w, K = r2.x;
      float v = 0.0, gf = 0.0;
      if (d2 < R2 && R2 > 0.0) {
        float t = 1.0 - d2 / R2;
        float tk1 = K == 0.0 ? 0.0 : amPowStiffness(t, K - 1.0);
        gf = -2.0 * I * K / R2 * tk1;
        v = K == 0.0 ? I : I * tk1 * t;
      }
      if (!useMax) {
        f += v;
        g += gf * d;
      } else if (v > f) {
        f = v;
        g = gf * d;
      }
    }
  }
  grad = g;
  return f - tr.reprojParams.w;
}

// closestSegmentSurface (standin.cpp): the nearest point on the capsules of the posed segments.
vec3 amClosestSegmentSurface(vec3 x) {
  float bestD = 3.4e38;
  vec3 sp = x;
  for (uint i = 0u; i < tr.mode.z; ++i) {
    vec3 a = tr.segs[2u * i].xyz, b = tr.segs[2u * i + 1u].xyz;
    float r = tr.segs[2u * i].w;
    vec3 c = amClosestOnSegment(x, a, b);
    float d = abs(length(x - c) - r);
    if (d < bestD) {
      bestD = d;
      vec3 dir = x - c;
      float len = length(dir);
      if (len < 1e-9) {
        vec3 ax = b - a;
        dir = cross(ax, abs(ax.x) < 0.9 * length(ax) ? vec3(1, 0, 0) : vec3(0, 1, 0));
        len = length(dir);
        if (len < 1e-12) {
          dir = vec3(0, 1, 0);
          len = 1.0;
        }
      }
      sp = c + dir / len * r;
    }
  }
  return sp;
}

// projectOntoField for one point: Newton steps x -= f grad / |grad|^2 (step
// limited), one fallback to the closest capsule surface when the gradient
// vanishes or Newton stalls; the point of smallest |f| seen, and -grad/|grad| there.
void amReproject(vec3 x, out vec3 best, out vec3 normal) {
  float T = tr.reprojParams.w, tol = tr.reprojParams.y, maxStep = tr.reprojParams.z;
  int maxIter = int(tr.mode.w);
  vec3 pos = x, bestG = vec3(0.0);
  best = x;
  float bestF = 3.4e38;
  int iter = 0;
  bool fellBack = false;
  for (int round = 0; round < 2 * maxIter + 2; ++round) {
    vec3 g;
    float f = amStandinField(pos, g);
    if (abs(f) < abs(bestF)) {
      bestF = f;
      best = pos;
      bestG = g;
    }
    if (abs(f) <= tol) break;
    float g2 = dot(g, g);
    bool noGradient = !(g2 > 1e-12 * T * T) || f <= -T * (1.0 - 1e-6);
    if (noGradient || iter >= maxIter) {
      if (fellBack || tr.mode.z == 0u) break;
      pos = amClosestSegmentSurface(pos);
      fellBack = true;
      iter = 0;
      continue;
    }
    vec3 step = -f * g / g2;
    float len = length(step);
    if (len > maxStep) step *= maxStep / len;
    pos += step;
    ++iter;
  }
  float gl = length(bestG);
  normal = gl > 0.0 ? -bestG / gl : vec3(0, 1, 0);
}

// One vertex: bind-space position p, normal n, skin influences, the stand-in
// binding (dp, m) and n~. worldPos is mesh.vert's wp at alpha = 0; worldNormal
// is unnormalised unless re-projected.
void amTransitionVertex(vec3 p, vec3 n, uvec4 j0, vec4 w0, uvec4 j1, vec4 w1, vec4 dpm, vec3 nt, out vec4 worldPos,
                        out vec3 worldNormal) {
  mat4 world = pc.model * amSkinMatrix(j0, w0, j1, w1);
  float a = amTransitionAlpha(dpm.w);
  vec3 q = p, nb = n;
  if (a != 0.0) {
    q = mix(p, p + dpm.xyz, a);
    vec3 nl = mix(n, nt, a);  // nlerp's normalisation is left to the final one
    nb = dot(nl, nl) > 1e-24 ? nl : nt;
  }
  worldPos = world * vec4(q, 1.0);
  worldNormal = transpose(inverse(mat3(world))) * nb;
  float r0 = tr.reprojParams.x;
  if ((tr.mode.x & AM_TR_REPROJECT) != 0u && a > r0) {
    vec3 proj, nf;
    amReproject(worldPos.xyz, proj, nf);
    float x = clamp((a - r0) / (1.0 - r0), 0.0, 1.0);
    float beta = a >= 1.0 ? 1.0 : x * x * (3.0 - 2.0 * x);
    worldPos = vec4(mix(worldPos.xyz, proj, beta), 1.0);
    float l = length(worldNormal);
    vec3 n0 = l > 0.0 ? worldNormal / l : vec3(0, 1, 0);
    vec3 nn = mix(n0, nf, beta);
    float ln = length(nn);
    worldNormal = ln > 1e-12 ? nn / ln : n0;
  }
}
