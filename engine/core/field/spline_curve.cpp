#include "core/field/spline_curve.h"

#include <algorithm>
#include <cmath>

namespace animorph {

CurvePoint evaluateCurve(const glm::vec3* p, int n, float s) {
  if (n <= 1) return {n == 1 ? p[0] : glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
  const CurveSpan c = curveSpan(p, n, s);
  const float u = c.u;
  CurvePoint r;
  r.position = c.position();
  r.tangent = (c.c1 + u * (2.0f * c.c2 + 3.0f * u * c.c3)) * float(c.spans);
  r.second = (2.0f * c.c2 + 6.0f * u * c.c3) * float(c.spans * c.spans);
  return r;
}

float closestCurveParameter(const glm::vec3* p, int n, const glm::vec3& x) {
  if (n <= 1) return 0.0f;
  const int samplesPerSpan = 16;
  int total = (n - 1) * samplesPerSpan;
  float best = 0.0f, bestD = INFINITY;
  for (int i = 0; i <= total; ++i) {
    float s = float(i) / float(total);
    glm::vec3 d = evaluateCurve(p, n, s).position - x;
    float dd = glm::dot(d, d);
    if (dd < bestD) {
      bestD = dd;
      best = s;
    }
  }
  float step = 1.0f / float(total);
  float lo = std::max(0.0f, best - step), hi = std::min(1.0f, best + step);
  float s = best;
  for (int it = 0; it < 8; ++it) {
    CurvePoint c = evaluateCurve(p, n, s);
    glm::vec3 d = c.position - x;
    float g = glm::dot(d, c.tangent);
    float h = glm::dot(c.tangent, c.tangent) + glm::dot(d, c.second);
    float next = h > 0.0f ? s - g / h : (g > 0.0f ? lo : hi);
    next = std::clamp(next, lo, hi);
    if (std::abs(next - s) < 1e-7f) {
      s = next;
      break;
    }
    s = next;
  }
  // Newton can only improve on the best sample; keep whichever is closer.
  glm::vec3 dn = evaluateCurve(p, n, s).position - x;
  return glm::dot(dn, dn) <= bestD ? s : best;
}

}  // namespace animorph
