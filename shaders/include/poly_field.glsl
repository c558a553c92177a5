// FieldProgram evaluation on the GPU: the scalar kernels of
// engine/core/field (field_kernels.cpp, skeleton.cpp, spline_curve.cpp,
// space_map.cpp, operators.h) ported line by line, the interval evaluator of
// FieldProgram::interval, and (poly_field_values.glsl) the batched value
// interpreter. Needs poly_common.glsl.
#include "morph_field.h"

// ------------------------------------------------------------ remap (operators.h: remapPotential)

// scale * p, or with K > 1 scale * K T p+ / ((K - 1) T + p+), linear below 0 with the slope at 0.
float amRemap(float p, float scale, float K, float T) {
  if (!(K > 1.0)) return scale * p;
  if (!(p > 0.0)) return scale * K * min(p, 0.0) / (K - 1.0);
  return scale * K * T * p / ((K - 1.0) * T + p);
}
// Its derivative dh/dp.
float amRemapSlope(float p, float scale, float K, float T) {
  if (!(K > 1.0)) return scale;
  if (!(p > 0.0)) return scale * K / (K - 1.0);
  float den = (K - 1.0) * T + p;
  return scale * K * (K - 1.0) * T * T / (den * den);
}
vec4 amRemap4(vec4 p, float scale, float K, float T) {
  return vec4(amRemap(p.x, scale, K, T), amRemap(p.y, scale, K, T), amRemap(p.z, scale, K, T), amRemap(p.w, scale, K, T));
}

// ------------------------------------------------------------ kernels

// atan2(y, x) for y > 0 (field_kernels.cpp: Cephes atanf polynomial), four at a time.
vec4 atan2PositiveY4(vec4 y, vec4 x) {
  vec4 ax = abs(x);
  vec4 mn = min(ax, y);
  vec4 mx = max(ax, y);
  bvec4 big = greaterThan(mn, 0.41421356237 * mx);
  vec4 t = mix(mn, mn - mx, big) / mix(mx, mn + mx, big);
  vec4 z = t * t;
  vec4 r = (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z - 3.33329491539e-1) * z * t + t;
  r += mix(vec4(0.0), vec4(0.78539816340), big);
  r = mix(r, 1.57079632679 - r, greaterThan(y, ax));
  r = mix(r, 3.14159265359 - r, lessThan(x, vec4(0.0)));
  return r;
}

// Intermediates of the convolution-segment kernel at four points (convolutionValues,
// convolutionGradients); record r0 = (b, l), r1 = (a, w), r2 = (S, cut2).
struct ConvTerms {
  vec4 dx, dy, dz;  // point - b
  vec4 u;           // along the axis
  vec4 lu, D, Q, invP, invDQ;
  vec4 F;           // the unweighted half kernel: the field is w F inside the cut
  bvec4 inCut;      // the point is within the cut distance (the field is 0 beyond)
};

// The terms from dd = |p - b|^2 and c.u = (p - b) . a; l, S, cut2 from the record.
void convolutionCore(inout ConvTerms c, vec4 dd, float l, float S, float cut2) {
  float S2 = S * S;
  vec4 perp2 = max(dd - c.u * c.u, vec4(0.0));
  vec4 Pp = 1.0 + S2 * perp2;
  c.D = 1.0 + S2 * dd;
  c.lu = l - c.u;
  vec4 e2 = dd - 2.0 * l * c.u + l * l;
  c.Q = 1.0 + S2 * e2;
  c.invP = 1.0 / Pp;
  vec4 p = sqrt(Pp);
  vec4 A = atan2PositiveY4(S * l * p, Pp - S2 * c.u * c.lu);
  c.invDQ = 1.0 / (c.D * c.Q);
  c.F = 0.5 * c.invP * ((c.u * c.Q + c.lu * c.D) * c.invDQ + A * p * c.invP / S);
  vec4 seg2 = mix(mix(perp2, e2, greaterThan(c.u, vec4(l))), dd, lessThan(c.u, vec4(0.0)));
  c.inCut = lessThanEqual(seg2, vec4(cut2));
}

ConvTerms convolutionTerms(vec4 x, vec4 y, vec4 z, vec4 r0, vec4 r1, vec4 r2) {
  ConvTerms c;
  c.dx = x - r0.x;
  c.dy = y - r0.y;
  c.dz = z - r0.z;
  vec4 dd = c.dx * c.dx + c.dy * c.dy + c.dz * c.dz;
  c.u = c.dx * r1.x + c.dy * r1.y + c.dz * r1.z;
  convolutionCore(c, dd, r0.w, r2.x, r2.y);
  return c;
}

// Weighted, cut convolution-segment field at four points (convolutionValues).
vec4 convolution4(vec4 x, vec4 y, vec4 z, vec4 r0, vec4 r1, vec4 r2) {
  ConvTerms c = convolutionTerms(x, y, z, r0, r1, r2);
  return mix(vec4(0.0), r1.w * c.F, c.inCut);
}

// The same at four points on a grid line: along x (axis 0) the points (v[c], s1, s2), along
// y (axis 1) (s1, v[c], s2). The constant coordinates' terms are taken once; the sums are
// those of convolutionTerms with the line's term first, (a + b) + c or (b + a) + c, equal
// bit for bit, so a group gives the values its points give (PointsL, poly_field_program.glsl).
vec4 convolutionLine4(vec4 v, float s1, float s2, uint axis, vec4 r0, vec4 r1, vec4 r2) {
  bool alongY = axis != 0u;
  float bv = alongY ? r0.y : r0.x, b1 = alongY ? r0.x : r0.y;
  float av = alongY ? r1.y : r1.x, a1 = alongY ? r1.x : r1.y;
  ConvTerms c;
  c.dx = v - bv;  // along the line
  float d1 = s1 - b1, d2 = s2 - r0.z;
  vec4 dd = c.dx * c.dx + d1 * d1 + d2 * d2;
  c.u = c.dx * av + d1 * a1 + d2 * r1.z;
  convolutionCore(c, dd, r0.w, r2.x, r2.y);
  return mix(vec4(0.0), r1.w * c.F, c.inCut);
}

// Calls BODY (which reads `r`, the pool record) for each convolution primitive of the
// Prims op op0 whose bit is set in the block mask at maskBase: one mask load per 32
// primitives, no loop trips for primitives that do not reach the block.
#define AM_FOR_BLOCK_CONVOLUTIONS(op0, maskBase, BODY)                  \
  {                                                                     \
    uint first_ = (op0).w, end_ = (op0).w + (op0).z;                    \
    for (uint g0_ = first_ & ~31u; g0_ < end_; g0_ += 32u) {            \
      uint bits_ = AM_BLOCK_MASK_WORD(maskBase, g0_ >> 5);              \
      if (g0_ < first_) bits_ &= ~0u << (first_ - g0_);                 \
      if (end_ - g0_ < 32u) bits_ &= (1u << (end_ - g0_)) - 1u;         \
      while (bits_ != 0u) {                                             \
        uint r = (op0).y + (g0_ + uint(findLSB(bits_)) - first_) * AM_REC_CONV; \
        bits_ &= bits_ - 1u;                                            \
        BODY                                                            \
      }                                                                 \
    }                                                                   \
  }

// Interval of the weighted, cut convolution field over the ball (c, rho) (convolutionIntervals).
vec2 convolutionInterval(vec3 c, float rho, vec4 r0, vec4 r1, vec4 r2) {
  float l = r0.w, S2 = r2.x * r2.x, cut2 = r2.y;
  vec3 d = c - r0.xyz;
  float uc = dot(d, r1.xyz);
  float perp2 = max(dot(d, d) - uc * uc, 0.0);
  float along = uc < 0.0 ? -uc : (uc > l ? uc - l : 0.0);
  float dseg = sqrt(perp2 + along * along);
  float ds = l * 0.125;
  float sumLo = 0.0, sumHi = 0.0;
  for (int q = 0; q < 8; ++q) {
    float s0 = ds * float(q), s1 = s0 + ds;
    float nearD = uc < s0 ? s0 - uc : (uc > s1 ? uc - s1 : 0.0);
    float farD = max(abs(s0 - uc), abs(s1 - uc));
    float rmin = max(sqrt(perp2 + nearD * nearD) - rho, 0.0);
    float rmax = sqrt(perp2 + farD * farD) + rho;
    float kmax = 1.0 / (1.0 + S2 * rmin * rmin);
    float kmin = 1.0 / (1.0 + S2 * rmax * rmax);
    sumHi += kmax * kmax;
    sumLo += kmin * kmin;
  }
  float wds = r1.w * ds;
  float dOut = dseg - rho, dIn = dseg + rho;
  bool none = dOut * dOut > cut2 && dOut > 0.0;
  bool inside = dIn * dIn <= cut2;
  return vec2(inside ? wds * sumLo * 0.9999 : 0.0, none ? 0.0 : wds * sumHi * 1.0001);
}

float powStiffness(float base, float k) {
  int ki = int(k);
  if (float(ki) == k && ki >= 0 && ki <= 8) {
    // By squaring, without a loop: lavapipe stops a shader's loops after 65 535 iterations, all
    // loops counted, and this loop ran 3 of every ~33 iterations of a skeletal kernel at 8 points.
    // (k = 2 and 3, the usual stiffnesses, give the CPU's repeated product bit for bit.)
    float b2 = base * base, b4 = b2 * b2;
    float r = (ki & 1) != 0 ? base : 1.0;
    if ((ki & 2) != 0) r *= b2;
    if ((ki & 4) != 0) r *= b4;
    if ((ki & 8) != 0) r *= b4 * b4;
    return r;
  }
  return pow(base, k);
}

// g = I (1 - d2/R^2)^k for d2 < R^2 (potential.h).
float skeletalPotential(float d2, float R, float I, float k) {
  float r2 = R * R;
  if (!(d2 < r2) || r2 <= 0.0) return 0.0;
  float t = 1.0 - d2 / r2;
  float tk1 = k == 0.0 ? 0.0 : powStiffness(t, k - 1.0);
  return k == 0.0 ? I : I * tk1 * t;
}

vec3 closestOnSegment(vec3 x, vec3 a, vec3 b) {
  vec3 ab = b - a;
  float l2 = dot(ab, ab);
  if (l2 <= 0.0) return a;
  float t = clamp(dot(x - a, ab) / l2, 0.0, 1.0);
  return a + t * ab;
}

vec3 closestOnBall(vec3 x, vec3 c, float r) {
  vec3 d = x - c;
  float l = length(d);
  if (l <= r) return x;
  return c + d * (r / l);
}

vec3 anyPerpendicular(vec3 n) {
  vec3 t = abs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0);
  return normalize(cross(n, t));
}

vec2 closest2(vec2 c, vec2 p, vec2 q) {
  vec2 pq = q - p;
  float l2 = dot(pq, pq);
  if (l2 <= 0.0) return p;
  float t = clamp(dot(c - p, pq) / l2, 0.0, 1.0);
  return p + t * pq;
}

vec3 closestOnDisc(vec3 x, vec3 c, vec3 n, float r) {
  vec3 d = x - c;
  vec3 inPlane = d - dot(d, n) * n;
  float l = length(inPlane);
  if (l > r) inPlane *= r / l;
  return c + inPlane;
}

vec3 closestOnCircle(vec3 x, vec3 c, vec3 n, float r) {
  vec3 d = x - c;
  vec3 inPlane = d - dot(d, n) * n;
  float l = length(inPlane);
  vec3 dir = l > 1e-12 ? inPlane / l : anyPerpendicular(n);
  return c + r * dir;
}

vec3 closestOnCone(vec3 x, vec3 a, vec3 b, float ra, float rb) {
  vec3 ab = b - a;
  float len = length(ab);
  if (len <= 1e-12) return closestOnDisc(x, a, vec3(0, 1, 0), max(ra, rb));
  vec3 axis = ab / len;
  vec3 d = x - a;
  float u = dot(d, axis);
  vec3 radial = d - u * axis;
  float rho = length(radial);
  vec3 rdir = rho > 1e-12 ? radial / rho : anyPerpendicular(axis);
  if (u >= 0.0 && u <= len && rho <= ra + (rb - ra) * (u / len)) return x;
  vec2 c = vec2(u, rho);
  vec2 v0 = vec2(0.0, 0.0), v1 = vec2(0.0, ra), v2 = vec2(len, rb), v3 = vec2(len, 0.0);
  vec2 best = closest2(c, v0, v1);
  float bestD = dot(best - c, best - c);
  vec2 q = closest2(c, v1, v2);
  float dq = dot(q - c, q - c);
  if (dq < bestD) {
    bestD = dq;
    best = q;
  }
  q = closest2(c, v2, v3);
  dq = dot(q - c, q - c);
  if (dq < bestD) best = q;
  return a + best.x * axis + best.y * rdir;
}

// Ericson, Real-Time Collision Detection, 5.1.5 (skeleton.cpp).
vec3 closestOnTriangle(vec3 p, vec3 a, vec3 b, vec3 c) {
  vec3 ab = b - a, ac = c - a, ap = p - a;
  float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  vec3 bp = p - b;
  float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  vec3 cp = p - c;
  float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  float va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  float denom = 1.0 / (va + vb + vc);
  if (isinf(denom) || isnan(denom)) return closestOnSegment(p, a, b);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Uniform Catmull-Rom curve through n control points pool[first ..] (spline_curve.cpp).
void evaluateCurve(uint first, int n, float s, out vec3 position, out vec3 tangent, out vec3 second) {
  if (n <= 1) {
    position = n == 1 ? POOLF(first).xyz : vec3(0.0);
    tangent = vec3(0.0);
    second = vec3(0.0);
    return;
  }
  int spans = n - 1;
  float x = clamp(s, 0.0, 1.0) * float(spans);
  int i = min(int(x), spans - 1);
  float u = x - float(i);
  vec3 p1 = POOLF(first + uint(i)).xyz, p2 = POOLF(first + uint(i + 1)).xyz;
  vec3 p0 = i > 0 ? POOLF(first + uint(i - 1)).xyz : 2.0 * p1 - p2;
  vec3 p3 = i + 2 < n ? POOLF(first + uint(i + 2)).xyz : 2.0 * p2 - p1;
  vec3 c1 = 0.5 * (p2 - p0);
  vec3 c2 = 0.5 * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3);
  vec3 c3 = 0.5 * (-p0 + 3.0 * p1 - 3.0 * p2 + p3);
  position = p1 + u * (c1 + u * (c2 + u * c3));
  tangent = (c1 + u * (2.0 * c2 + 3.0 * u * c3)) * float(spans);
  second = (2.0 * c2 + 6.0 * u * c3) * float(spans * spans);
}

vec3 curvePosition(uint first, int n, float s) {
  vec3 p, t, c;
  evaluateCurve(first, n, s, p, t, c);
  return p;
}

// closestCurveParameter: dense sampling, then Newton in the best sample's neighbourhood.
vec3 closestOnCurve(uint first, int n, vec3 x) {
  if (n <= 1) return curvePosition(first, n, 0.0);
  const int samplesPerSpan = 16;
  int total = (n - 1) * samplesPerSpan;
  float best = 0.0, bestD = kInf;
  for (int i = 0; i <= total; ++i) {
    float s = float(i) / float(total);
    vec3 d = curvePosition(first, n, s) - x;
    float dd = dot(d, d);
    if (dd < bestD) {
      bestD = dd;
      best = s;
    }
  }
  float sampleStep = 1.0 / float(total);
  float lo = max(0.0, best - sampleStep), hi = min(1.0, best + sampleStep);
  float s = best;
  for (int it = 0; it < 8; ++it) {
    vec3 pos, tan, sec;
    evaluateCurve(first, n, s, pos, tan, sec);
    vec3 d = pos - x;
    float g = dot(d, tan);
    float h = dot(tan, tan) + dot(d, sec);
    float next = h > 0.0 ? s - g / h : (g > 0.0 ? lo : hi);
    next = clamp(next, lo, hi);
    if (abs(next - s) < 1e-7) {
      s = next;
      break;
    }
    s = next;
  }
  vec3 pn = curvePosition(first, n, s);
  vec3 dn = pn - x;
  return dot(dn, dn) <= bestD ? pn : curvePosition(first, n, best);
}

// Closest point of skeletal primitive record rec to x (closestOnSkeleton).
vec3 closestOnSkeleton(uint rec, vec3 x) {
  vec4 r0 = POOLF(rec), r1 = POOLF(rec + 1u), r2 = POOLF(rec + 2u);
  uint kindBits = floatBitsToUint(r0.w);
  uint kind = kindBits & 0xffu;
  if (AM_HAS_SKEL(AM_SKEL_POINT) && kind == AM_SKEL_POINT) return r0.xyz;
  if (AM_HAS_SKEL(AM_SKEL_SPHERE) && kind == AM_SKEL_SPHERE) return closestOnBall(x, r0.xyz, r1.w);
  if (AM_HAS_SKEL(AM_SKEL_SEGMENT) && kind == AM_SKEL_SEGMENT) return closestOnSegment(x, r0.xyz, r1.xyz);
  if (AM_HAS_SKEL(AM_SKEL_CYLINDER) && kind == AM_SKEL_CYLINDER) return closestOnCone(x, r0.xyz, r1.xyz, r1.w, r1.w);
  if (AM_HAS_SKEL(AM_SKEL_CONE) && kind == AM_SKEL_CONE) return closestOnCone(x, r0.xyz, r1.xyz, r1.w, r2.w);
  if (AM_HAS_SKEL(AM_SKEL_DISC) && kind == AM_SKEL_DISC) return closestOnDisc(x, r0.xyz, r1.xyz, r1.w);
  if (AM_HAS_SKEL(AM_SKEL_CIRCLE) && kind == AM_SKEL_CIRCLE) return closestOnCircle(x, r0.xyz, r1.xyz, r1.w);
  if (AM_HAS_SKEL(AM_SKEL_TRIANGLE) && kind == AM_SKEL_TRIANGLE) return closestOnTriangle(x, r0.xyz, r1.xyz, r2.xyz);
  if (AM_LACKS_SKEL(AM_SKEL_CURVE)) return r0.xyz;  // unreachable: the variant has every kind its programs use
  return closestOnCurve(floatBitsToUint(POOLF(rec + 3u).w), int(kindBits >> 8), x);
}

// Whether q lies outside the capsule enclosing skeletal record rec (the rejection of
// skeletalLoop: the potential is 0 there).
bool outsideSkeletalCapsule(uint rec, vec3 q) {
  vec4 r4 = POOLF(rec + 4u), r5 = POOLF(rec + 5u);
  vec3 ca = r4.xyz, ab = r5.xyz - r4.xyz;
  float l2 = dot(ab, ab);
  float t = l2 > 0.0 ? clamp(dot(q - ca, ab) / l2, 0.0, 1.0) : 0.0;
  vec3 e = q - (ca + t * ab);
  return dot(e, e) >= r4.w * r4.w;
}

// Skeletal potential of record rec at x, with the enclosing-capsule rejection of skeletalLoop.
float skeletalValue(uint rec, vec3 q) {
  if (outsideSkeletalCapsule(rec, q)) return 0.0;
  vec4 r3 = POOLF(rec + 3u);
  vec3 d = q - closestOnSkeleton(rec, q);
  return skeletalPotential(dot(d, d), r3.x, r3.y, r3.z);
}

// Canal surface T max(0, 2 - dist / R) (capsuleLoop): record (a, R), (b, 0).
float capsuleValue(uint rec, vec3 q, float T) {
  vec4 r0 = POOLF(rec), r1 = POOLF(rec + 1u);
  if (r0.w <= 0.0) return 0.0;
  float dist = length(q - closestOnSegment(q, r0.xyz, r1.xyz));
  float v = T * (2.0 - dist * (1.0 / r0.w));
  return v <= 0.0 ? 0.0 : v;
}

// ------------------------------------------------------------ space maps

vec3 bendInverse(vec3 Pw, float kappa, float len) {
  float c = 1.0 / kappa;
  float X = Pw.x, Y = Pw.y, Z = Pw.z;
  float theta = atan(Z, c - Y);
  float thetaL = kappa * len;
  if (Z < 0.0 || theta < 0.0) return Pw;
  if (theta <= thetaL) {
    float rho = sqrt((c - Y) * (c - Y) + Z * Z);
    return vec3(X, c - rho, theta / kappa);
  }
  float s = sin(thetaL), co = cos(thetaL);
  vec3 C = vec3(0.0, (1.0 - co) / kappa, s / kappa);
  vec3 N = vec3(0.0, co, -s), Tt = vec3(0.0, s, co);
  vec3 v = Pw - C;
  return vec3(v.x, dot(v, N), dot(v, Tt) + len);
}

// World -> child point through map record m (SpaceMap::toLocal): r0..r2 = columns
// of `linear` (w: kind, length, k0), r3 = (origin, k1).
vec3 mapToLocal(uint m, vec3 x) {
  vec4 r0 = POOLF(m), r1 = POOLF(m + 1u), r2 = POOLF(m + 2u), r3 = POOLF(m + 3u);
  mat3 L = mat3(r0.xyz, r1.xyz, r2.xyz);
  uint kind = floatBitsToUint(r0.w);
  vec3 Pw = L * (x - r3.xyz);
  if (AM_AFFINE_MAPS_ONLY) return Pw;
  if (AM_HAS_MAP(AM_MAP_AFFINE) && kind == AM_MAP_AFFINE) return Pw;
  float len = r1.w, k0 = r2.w, k1 = r3.w;
  vec3 Lc = Pw;
  if (AM_HAS_MAP(AM_MAP_TWIST) && kind == AM_MAP_TWIST) {
    float zc = clamp(Pw.z, 0.0, len);
    float phi = k0 * zc;
    float c = cos(phi), s = sin(phi);
    Lc = vec3(Pw.x * c + Pw.y * s, -Pw.x * s + Pw.y * c, Pw.z);
  } else if (AM_HAS_MAP(AM_MAP_TAPER) && kind == AM_MAP_TAPER) {
    float zc = clamp(Pw.z, 0.0, len);
    float sc = k0 + (k1 - k0) * (zc / len);
    Lc = vec3(Pw.x / sc, Pw.y / sc, Pw.z);
  } else if (AM_HAS_MAP(AM_MAP_BEND)) {
    if (abs(k0) < 1e-6) {
      Lc = Pw;
    } else if (k0 > 0.0) {
      Lc = bendInverse(Pw, k0, len);
    } else {
      vec3 Lm = bendInverse(vec3(Pw.x, -Pw.y, Pw.z), -k0, len);
      Lc = vec3(Lm.x, -Lm.y, Lm.z);
    }
  }
  return r3.xyz + transpose(L) * Lc;
}

// Upper bound of how much map m stretches distances on the ball (c, radius) (localStretchBound).
float mapStretchBound(uint m, vec3 centre, float radius) {
  vec4 r0 = POOLF(m), r1 = POOLF(m + 1u), r2 = POOLF(m + 2u), r3 = POOLF(m + 3u);
  uint kind = floatBitsToUint(r0.w);
  if (AM_AFFINE_MAPS_ONLY)
    return sqrt(dot(r0.xyz, r0.xyz) + dot(r1.xyz, r1.xyz) + dot(r2.xyz, r2.xyz));
  if (kind == AM_MAP_AFFINE) return sqrt(dot(r0.xyz, r0.xyz) + dot(r1.xyz, r1.xyz) + dot(r2.xyz, r2.xyz));
  mat3 L = mat3(r0.xyz, r1.xyz, r2.xyz);
  vec3 Lc = L * (centre - r3.xyz);
  float rMax = sqrt(Lc.x * Lc.x + Lc.y * Lc.y) + radius;
  float len = r1.w, k0 = r2.w, k1 = r3.w;
  if (AM_HAS_MAP(AM_MAP_TWIST) && kind == AM_MAP_TWIST) return 1.0 + abs(k0) * rMax;
  if (AM_HAS_MAP(AM_MAP_TAPER) && kind == AM_MAP_TAPER) {
    float smin = min(k0, k1);
    if (smin <= 0.0) return kInf;
    return 1.0 / smin + abs(k1 - k0) / len * rMax / (smin * smin);
  }
  float kap = abs(k0);
  if (kap < 1e-6) return 1.0;
  float minDist = 1.0 / kap - rMax;
  if (minDist <= 0.0) return kInf;
  return max(1.0, 1.0 / (kap * minDist));
}

// ------------------------------------------------------------ intervals

float paramAt(uint index) { return POOLF(index >> 2)[index & 3u]; }

// Interval of f = p - T of the program's ops [opBegin, opBegin + opCount) over
// the ball (centre, radius), primitives restricted to the block mask at maskBase
// (FieldProgram::interval on the specialised program).
vec2 programInterval(uint opBegin, uint opCount, float T, vec3 centre, float radius, uint maskBase) {
  vec2 st[AM_POLY_MAX_STACK];
  vec4 balls[AM_POLY_MAX_MAP_DEPTH];
  int sp = 0, level = 0;
  vec2 last = vec2(-T);  // AM_STACKLESS: the interval of the program's only op
  vec3 c = centre;
  float rho = radius;
  for (uint i = 0u; i < opCount; ++i) {
    uint o = opBegin + i * AM_REC_OP;
    uvec4 op0 = POOLU(o);
    vec4 op1 = POOLF(o + 1u);
    uint code = op0.x & 0xffu;
    if (AM_HAS_OP(AM_OP_PRIMS) && code == AM_OP_PRIMS) {
      uint cls = (op0.x >> 8) & 0xffu;
      bool cmax = ((op0.x >> 16) & 1u) != 0u;
      vec2 acc = vec2(0.0);
      for (uint k = 0u; k < op0.z; ++k) {
        if (!primActive(maskBase, op0.w + k)) continue;
        vec2 v = vec2(0.0);
        if (AM_HAS_CLASS(AM_PRIM_CONVOLUTION) && cls == AM_PRIM_CONVOLUTION) {
          uint r = op0.y + k * AM_REC_CONV;
          acc += convolutionInterval(c, rho, POOLF(r), POOLF(r + 1u), POOLF(r + 2u));
          continue;
        } else if (AM_HAS_CLASS(AM_PRIM_SKELETAL) && cls == AM_PRIM_SKELETAL) {
          uint r = op0.y + k * AM_REC_SKEL;
          vec4 r3 = POOLF(r + 3u);
          float d = length(c - closestOnSkeleton(r, c));
          float dm = max(0.0, d - rho);
          float g0 = skeletalPotential(dm * dm, r3.x, r3.y, r3.z);
          float g1 = skeletalPotential((d + rho) * (d + rho), r3.x, r3.y, r3.z);
          v = vec2(min(g0, g1), max(g0, g1));
        } else if (AM_HAS_CLASS(AM_PRIM_CAPSULE)) {
          uint r = op0.y + k * AM_REC_CAPSULE;
          vec4 r0 = POOLF(r), r1 = POOLF(r + 1u);
          float d = length(c - closestOnSegment(c, r0.xyz, r1.xyz));
          float R = r0.w;
          float gFar = R > 0.0 ? T * max(0.0, 2.0 - (d + rho) / R) : 0.0;
          float gNear = R > 0.0 ? T * max(0.0, 2.0 - max(0.0, d - rho) / R) : 0.0;
          v = vec2(gFar, gNear);
        }
        acc = cmax ? max(acc, v) : acc + v;
      }
      if (AM_STACKLESS) last = acc - vec2(T);
      else st[sp++] = acc;
    } else if (AM_HAS_OP(AM_OP_CONST) && code == AM_OP_CONST) {
      st[sp++] = vec2(op1.z);
    } else if (AM_HAS_OP(AM_OP_BEGINMAP) && code == AM_OP_BEGINMAP) {
      if (!anyPrimActive(maskBase, op0.w, op0.y)) {  // the subtree is constant here (gpu_field_program.cpp)
        st[sp++] = vec2(op1.z);
        i += floatBitsToUint(op1.w);
        continue;
      }
      uint m = floatBitsToUint(op1.y);
      balls[level++] = vec4(c, rho);
      float stretch = mapStretchBound(m, c, rho);
      c = mapToLocal(m, c);
      rho = isinf(stretch) ? kInf : rho * stretch * 1.0001;
    } else if (AM_HAS_OP(AM_OP_ENDMAP) && code == AM_OP_ENDMAP) {
      vec4 b = balls[--level];
      c = b.xyz;
      rho = b.w;
    } else if (AM_HAS_OPERATORS) {
      int n = int(op0.z);
      int base = sp - n;
      uint prm = floatBitsToUint(op1.x);
      vec2 r = st[base];
      if (AM_HAS_OP(AM_OP_SUM) && code == AM_OP_SUM) {
        for (int k = 1; k < n; ++k) r += st[base + k];
      } else if (AM_HAS_OP(AM_OP_MAX) && code == AM_OP_MAX) {
        for (int k = 1; k < n; ++k) r = max(r, st[base + k]);
      } else if (AM_HAS_OP(AM_OP_MIN) && code == AM_OP_MIN) {
        for (int k = 1; k < n; ++k) r = min(r, st[base + k]);
      } else if (AM_HAS_OP(AM_OP_HYPERBLEND) && code == AM_OP_HYPERBLEND) {
        float q = paramAt(prm);
        vec2 sum = vec2(0.0);
        for (int k = 0; k < n; ++k) {
          vec2 v = max(st[base + k], vec2(0.0));
          sum.x += v.x > 0.0 ? pow(v.x, q) : 0.0;
          sum.y += v.y > 0.0 ? pow(v.y, q) : 0.0;
        }
        r = vec2(sum.x > 0.0 ? pow(sum.x, 1.0 / q) : 0.0, sum.y > 0.0 ? pow(sum.y, 1.0 / q) : 0.0);
      } else if (AM_HAS_OP(AM_OP_DIFFERENCE) && code == AM_OP_DIFFERENCE) {
        vec2 b = st[base + 1];
        r = vec2(min(r.x, 2.0 * T - b.y), min(r.y, 2.0 * T - b.x));
      } else if (AM_HAS_OP(AM_OP_RUNION) && code == AM_OP_RUNION) {
        vec2 b = st[base + 1];
        r = vec2(T + amRUnion(r.x - T, b.x - T), T + amRUnion(r.y - T, b.y - T));
      } else if (AM_HAS_OP(AM_OP_RINTERSECTION) && code == AM_OP_RINTERSECTION) {
        vec2 b = st[base + 1];
        r = vec2(T + amRIntersection(r.x - T, b.x - T), T + amRIntersection(r.y - T, b.y - T));
      } else if (AM_HAS_OP(AM_OP_BOUNDEDBLEND) && code == AM_OP_BOUNDEDBLEND) {
        vec2 b = st[base + 1];
        float a0 = paramAt(prm);
        r = vec2(T + amRUnion(r.x - T, b.x - T) + min(0.0, a0), T + amRUnion(r.y - T, b.y - T) + max(0.0, a0));
      } else if (AM_HAS_OP(AM_OP_REMAP) && code == AM_OP_REMAP) {
        float sc = paramAt(prm), k = paramAt(prm + 1u);
        vec2 m = vec2(amRemap(r.x, sc, k, T), amRemap(r.y, sc, k, T));
        r = vec2(min(m.x, m.y), max(m.x, m.y));
      }
      if (isnan(r.x)) r.x = -kInf;
      if (isnan(r.y)) r.y = kInf;
      sp = base + 1;
      st[base] = r;
    }
  }
  if (AM_STACKLESS) return last;
  return sp > 0 ? st[0] - vec2(T) : vec2(-T);
}

vec2 guardInterval(vec2 r) { return vec2(isnan(r.x) ? -kInf : r.x, isnan(r.y) ? kInf : r.y); }

// Interval of the combined field (one program, or the morph of two) over the ball.
vec2 combinedInterval(vec3 centre, float radius, uint maskBase) {
  vec2 a = programInterval(gOps.x, gOps.y, P.thresholds.x, centre, radius, maskBase);
  if (AM_SINGLE_ONLY) return a;
  if (P.modes.x == AM_COMBINE_SINGLE) return a;
  vec2 b = programInterval(gOps.z, gOps.w, P.thresholds.y, centre, radius, maskBase);
  if (AM_HAS_COMBINE(AM_COMBINE_INTERPOLATE) && P.modes.x == AM_COMBINE_INTERPOLATE) {
    float w = P.morph0.x;
    vec2 ia = (1.0 - w) * a, ib = w * b;
    return guardInterval(vec2(min(ia.x, ia.y) + min(ib.x, ib.y), max(ia.x, ia.y) + max(ib.x, ib.y)));
  }
  if (AM_LACKS_COMBINE(AM_COMBINE_SPACETIME)) return a;  // unreachable: the variant has its combine mode
  float tau = P.morph0.z * P.morph0.y, tau1 = P.morph0.z * (P.morph0.y - 1.0);
  // R-functions are non-decreasing in each argument: map the ends.
  vec2 g1 = guardInterval(vec2(amRIntersection(a.x, -tau), amRIntersection(a.y, -tau)));
  vec2 g2 = guardInterval(vec2(amRIntersection(b.x, tau1), amRIntersection(b.y, tau1)));
  float a0 = P.morph0.w;
  return guardInterval(vec2(amRUnion(g1.x, g2.x) + min(0.0, a0), amRUnion(g1.y, g2.y) + max(0.0, a0)));
}

// Sign of the field over the cell box [c0, c0 + cnt], proved by its interval over the
// primitives of the mask at maskBase with the CPU polygoniser's margin and grid-boundary rule
// (a box touching the grid boundary is never proved inside): -1 outside, 1 inside, 0 when the
// box can hold surface.
int boxSign(uvec3 c0, uvec3 cnt, uint maskBase) {
  vec3 lo = cornerPosition(c0), hi = cornerPosition(c0 + cnt);
  bool boundary = any(equal(c0, uvec3(0u))) || any(greaterThanEqual(c0 + cnt, P.gridCells.xyz));
  vec2 iv = combinedInterval(0.5 * (lo + hi), 0.5 * length(hi - lo), maskBase);
  float margin = P.thresholds.z;
  if (iv.y < -margin) return -1;
  if (iv.x > margin && !boundary) return 1;
  return 0;
}

bool canHoldSurface(uvec3 c0, uvec3 cnt, uint maskBase) { return boxSign(c0, cnt, maskBase) == 0; }
