#include "core/field/space_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/field/space_map_simd.h"

namespace animorph {

namespace {

// Rows e_x, e_y, e_z with e_z along axis and e_y as close to `up` as possible.
glm::mat3 warpFrame(const glm::vec3& axis, const glm::vec3& up) {
  glm::vec3 ez = glm::normalize(axis);
  glm::vec3 ey = up - glm::dot(up, ez) * ez;
  if (glm::length(ey) < 1e-6f) {
    glm::vec3 t = std::abs(ez.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    ey = t - glm::dot(t, ez) * ez;
  }
  ey = glm::normalize(ey);
  glm::vec3 ex = glm::cross(ey, ez);
  return glm::transpose(glm::mat3(ex, ey, ez));  // rows
}

glm::mat3 rowsToMat(const glm::vec3& r0, const glm::vec3& r1, const glm::vec3& r2) {
  return glm::transpose(glm::mat3(r0, r1, r2));
}

// Bend with curvature kappa > 0 in the warp frame: world (X,Y,Z) -> local.
glm::vec3 bendInverse(const glm::vec3& P, float kappa, float len, glm::mat3* J) {
  float c = 1.0f / kappa;
  float X = P.x, Y = P.y, Z = P.z;
  float theta = std::atan2(Z, c - Y);
  float thetaL = kappa * len;
  if (Z < 0.0f || theta < 0.0f) {
    if (J) *J = glm::mat3(1.0f);
    return P;
  }
  if (theta <= thetaL) {
    float rho = std::sqrt((c - Y) * (c - Y) + Z * Z);
    if (J) {
      glm::vec3 r0(1, 0, 0);
      glm::vec3 r1(0, (c - Y) / rho, -Z / rho);
      glm::vec3 r2(0, Z / (kappa * rho * rho), (c - Y) / (kappa * rho * rho));
      *J = rowsToMat(r0, r1, r2);
    }
    return {X, c - rho, theta / kappa};
  }
  float s = std::sin(thetaL), co = std::cos(thetaL);
  glm::vec3 C(0.0f, (1.0f - co) / kappa, s / kappa);
  glm::vec3 N(0.0f, co, -s), T(0.0f, s, co);
  glm::vec3 v = P - C;
  if (J) *J = rowsToMat(glm::vec3(1, 0, 0), N, T);
  return {v.x, glm::dot(v, N), glm::dot(v, T) + len};
}

glm::vec3 bendForward(const glm::vec3& p, float kappa, float len) {
  float zc = std::clamp(p.z, 0.0f, len);
  float theta = kappa * zc;
  float s = std::sin(theta), co = std::cos(theta);
  glm::vec3 C(0.0f, (1.0f - co) / kappa, s / kappa);
  glm::vec3 N(0.0f, co, -s), T(0.0f, s, co);
  return C + glm::vec3(p.x, 0, 0) + p.y * N + (p.z - zc) * T;
}

}  // namespace

SpaceMap makeAffineMap(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale) {
  SpaceMap m;
  m.kind = SpaceMapKind::Affine;
  glm::mat3 R = glm::mat3_cast(glm::normalize(rotation));
  glm::mat3 S(1.0f);
  S[0][0] = scale.x;
  S[1][1] = scale.y;
  S[2][2] = scale.z;
  m.forwardLinear = R * S;
  m.linear = glm::inverse(m.forwardLinear);
  m.origin = translation;
  return m;
}

SpaceMap makeTwistMap(const glm::vec3& a, const glm::vec3& b, float angle) {
  SpaceMap m;
  m.kind = SpaceMapKind::Twist;
  m.length = std::max(glm::length(b - a), 1e-9f);
  m.linear = warpFrame(b - a, glm::vec3(0, 1, 0));
  m.origin = a;
  m.k0 = angle / m.length;
  return m;
}

SpaceMap makeTaperMap(const glm::vec3& a, const glm::vec3& b, float scaleA, float scaleB) {
  SpaceMap m;
  m.kind = SpaceMapKind::Taper;
  m.length = std::max(glm::length(b - a), 1e-9f);
  m.linear = warpFrame(b - a, glm::vec3(0, 1, 0));
  m.origin = a;
  m.k0 = scaleA;
  m.k1 = scaleB;
  return m;
}

SpaceMap makeBendMap(const glm::vec3& a, const glm::vec3& b, float angle, const glm::vec3& direction) {
  SpaceMap m;
  m.kind = SpaceMapKind::Bend;
  m.length = std::max(glm::length(b - a), 1e-9f);
  m.linear = warpFrame(b - a, direction);
  m.origin = a;
  m.k0 = angle / m.length;
  return m;
}

glm::vec3 SpaceMap::toLocal(const glm::vec3& x, glm::mat3* J) const {
  if (kind == SpaceMapKind::Affine) {
    if (J) *J = linear;
    return linear * (x - origin);
  }
  glm::vec3 P = linear * (x - origin);  // warp frame coordinates
  glm::vec3 L = P;
  glm::mat3 Jl(1.0f);
  switch (kind) {
    case SpaceMapKind::Twist: {
      float zc = std::clamp(P.z, 0.0f, length);
      float phi = k0 * zc;
      float c = std::cos(phi), s = std::sin(phi);
      L = {P.x * c + P.y * s, -P.x * s + P.y * c, P.z};
      if (J) {
        float dphi = (P.z > 0.0f && P.z < length) ? k0 : 0.0f;
        // columns: d/dX, d/dY, d/dZ
        Jl = glm::mat3(glm::vec3(c, -s, 0), glm::vec3(s, c, 0),
                       glm::vec3(dphi * (-P.x * s + P.y * c), dphi * (-P.x * c - P.y * s), 1.0f));
      }
      break;
    }
    case SpaceMapKind::Taper: {
      float zc = std::clamp(P.z, 0.0f, length);
      float sc = k0 + (k1 - k0) * (zc / length);
      float ds = (P.z > 0.0f && P.z < length) ? (k1 - k0) / length : 0.0f;
      L = {P.x / sc, P.y / sc, P.z};
      if (J)
        Jl = glm::mat3(glm::vec3(1.0f / sc, 0, 0), glm::vec3(0, 1.0f / sc, 0),
                       glm::vec3(-P.x * ds / (sc * sc), -P.y * ds / (sc * sc), 1.0f));
      break;
    }
    case SpaceMapKind::Bend: {
      if (std::abs(k0) < 1e-6f) {
        L = P;
      } else if (k0 > 0.0f) {
        L = bendInverse(P, k0, length, J ? &Jl : nullptr);
      } else {
        glm::vec3 Pm(P.x, -P.y, P.z);
        glm::vec3 Lm = bendInverse(Pm, -k0, length, J ? &Jl : nullptr);
        L = {Lm.x, -Lm.y, Lm.z};
        glm::mat3 M(1.0f);
        M[1][1] = -1.0f;
        Jl = M * Jl * M;
      }
      break;
    }
    case SpaceMapKind::Affine: break;
  }
  glm::mat3 Bt = glm::transpose(linear);
  if (J) *J = Bt * Jl * linear;
  return origin + Bt * L;
}

glm::vec3 SpaceMap::toWorld(const glm::vec3& c) const {
  if (kind == SpaceMapKind::Affine) {
#if defined(__SSE2__)
    return simd::vec3Of(simd::affineToWorld(simd::lanes(forwardLinear[0]), simd::lanes(forwardLinear[1]),
                                            simd::lanes(forwardLinear[2]), simd::lanes(origin), simd::load3(c)));
#else
    return origin + forwardLinear * c;
#endif
  }
  glm::vec3 L = linear * (c - origin);
  glm::vec3 P = L;
  switch (kind) {
    case SpaceMapKind::Twist: {
      float phi = k0 * std::clamp(L.z, 0.0f, length);
      float co = std::cos(phi), s = std::sin(phi);
      P = {L.x * co - L.y * s, L.x * s + L.y * co, L.z};
      break;
    }
    case SpaceMapKind::Taper: {
      float sc = k0 + (k1 - k0) * (std::clamp(L.z, 0.0f, length) / length);
      P = {L.x * sc, L.y * sc, L.z};
      break;
    }
    case SpaceMapKind::Bend: {
      if (std::abs(k0) < 1e-6f) P = L;
      else if (k0 > 0.0f) P = bendForward(L, k0, length);
      else {
        glm::vec3 Pm = bendForward(glm::vec3(L.x, -L.y, L.z), -k0, length);
        P = {Pm.x, -Pm.y, Pm.z};
      }
      break;
    }
    case SpaceMapKind::Affine: P = L; break;
  }
  return origin + glm::transpose(linear) * P;
}

Bounds SpaceMap::worldBounds(const Bounds& child) const {
  Bounds out;
  if (child.empty()) return out;
  if (!std::isfinite(child.min.x) || !std::isfinite(child.max.x) || !std::isfinite(child.min.y) ||
      !std::isfinite(child.max.y) || !std::isfinite(child.min.z) || !std::isfinite(child.max.z)) {
    out.min = glm::vec3(-INFINITY);
    out.max = glm::vec3(INFINITY);
    return out;
  }
  if (kind == SpaceMapKind::Affine) {
    // toWorld of the 8 corners, origin + ((m[0] x + m[1] y) + m[2] z) per component as glm computes
    // it, with the 6 column products shared between corners: the same values, a third of the work.
    const glm::mat3& m = forwardLinear;
#if defined(__SSE2__)
    {
      __m128 lo, hi;
      if (simd::affineWorldBox(simd::lanes(m[0]), simd::lanes(m[1]), simd::lanes(m[2]), simd::lanes(origin),
                               simd::load3(child.min), simd::load3(child.max), lo, hi)) {
        out.min = simd::vec3Of(lo);
        out.max = simd::vec3Of(hi);
        return out;
      }
    }
#endif
    const glm::vec3 px[2] = {m[0] * child.min.x, m[0] * child.max.x};
    const glm::vec3 py[2] = {m[1] * child.min.y, m[1] * child.max.y};
    const glm::vec3 pz[2] = {m[2] * child.min.z, m[2] * child.max.z};
    // Rounded addition is monotonic in each operand, so per component the smallest (largest) corner
    // image is the sum of the smallest (largest) products: the box without visiting the corners.
    // A zero bound (whose sign depends on which corner gave it) takes the corner loop below.
    bool zero = false;
    for (int k = 0; k < 3; ++k) {
      out.min[k] = origin[k] + ((std::min(px[0][k], px[1][k]) + std::min(py[0][k], py[1][k])) +
                                std::min(pz[0][k], pz[1][k]));
      out.max[k] = origin[k] + ((std::max(px[0][k], px[1][k]) + std::max(py[0][k], py[1][k])) +
                                std::max(pz[0][k], pz[1][k]));
      zero |= out.min[k] == 0.0f || out.max[k] == 0.0f;
    }
    if (!zero) return out;
    out = Bounds{};
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 &a = px[i & 1], &b = py[(i >> 1) & 1], &c = pz[(i >> 2) & 1];
      out.add(origin + glm::vec3(a.x + b.x + c.x, a.y + b.y + c.y, a.z + b.z + c.z));
    }
    return out;
  }
  // Warps: image of a 9^3 lattice, padded by Lipschitz constant * half the lattice diagonal.
  float rMax = 0.0f;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c{i & 1 ? child.max.x : child.min.x, i & 2 ? child.max.y : child.min.y,
                i & 4 ? child.max.z : child.min.z};
    glm::vec3 L = linear * (c - origin);
    rMax = std::max(rMax, std::sqrt(L.x * L.x + L.y * L.y));
  }
  float lip = 1.0f;
  switch (kind) {
    case SpaceMapKind::Twist: lip = 1.0f + std::abs(k0) * rMax; break;
    case SpaceMapKind::Taper:
      lip = std::max({1.0f, std::abs(k0), std::abs(k1)}) + std::abs(k1 - k0) / length * rMax;
      break;
    case SpaceMapKind::Bend: lip = 1.0f + std::abs(k0) * rMax; break;
    case SpaceMapKind::Affine: break;
  }
  const int n = 8;
  glm::vec3 step = (child.max - child.min) / float(n);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) out.add(toWorld(child.min + step * glm::vec3(float(i), float(j), float(k))));
  float pad = lip * 0.5f * glm::length(step) + 1e-6f;
  out.min -= glm::vec3(pad);
  out.max += glm::vec3(pad);
  return out;
}

float SpaceMap::localStretchBound(const glm::vec3& centre, float radius) const {
  if (kind == SpaceMapKind::Affine) {
    // Spectral norm <= Frobenius norm.
    float f = 0.0f;
    for (int c = 0; c < 3; ++c) f += glm::dot(linear[c], linear[c]);
    return std::sqrt(f);
  }
  glm::vec3 L = linear * (centre - origin);
  float rMax = std::sqrt(L.x * L.x + L.y * L.y) + radius;
  switch (kind) {
    case SpaceMapKind::Twist: return 1.0f + std::abs(k0) * rMax;
    case SpaceMapKind::Taper: {
      float smin = std::min(k0, k1);
      if (smin <= 0.0f) return INFINITY;
      return 1.0f / smin + std::abs(k1 - k0) / length * rMax / (smin * smin);
    }
    case SpaceMapKind::Bend: {
      // d(local)/d(world) grows like 1 / (kappa * distance to the bend centre).
      float kap = std::abs(k0);
      if (kap < 1e-6f) return 1.0f;
      float minDist = 1.0f / kap - rMax;
      if (minDist <= 0.0f) return INFINITY;
      return std::max(1.0f, 1.0f / (kap * minDist));
    }
    case SpaceMapKind::Affine: break;
  }
  return INFINITY;
}

}  // namespace animorph
