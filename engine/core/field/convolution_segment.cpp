#include "core/field/convolution_segment.h"

#include <algorithm>

namespace animorph {

namespace {
// The largest F over the points at distance r from the segment: the point
// beside the middle (a symmetric, decreasing kernel sees the most segment
// there; points beyond an end see less).
double fieldMaxAtDistance(double r, double l, double S) {
  glm::dvec3 b(0.0), a(1.0, 0.0, 0.0), x(0.5 * l, r, 0.0);
  return convolutionSegmentField<double>(x, b, a, l, S);
}
}  // namespace

double convolutionCutoffRadius(double length, double S, double weight, double threshold, double eps) {
  double target = eps * threshold;
  if (weight <= 0.0 || length <= 0.0) return 0.0;
  if (target <= 0.0) return INFINITY;
  double lo = 0.0, hi = 1.0 / S;
  while (weight * fieldMaxAtDistance(hi, length, S) >= target && hi < 1e6) hi *= 2.0;
  for (int i = 0; i < 60; ++i) {
    double mid = 0.5 * (lo + hi);
    if (weight * fieldMaxAtDistance(mid, length, S) >= target) lo = mid;
    else hi = mid;
  }
  return hi;
}

}  // namespace animorph
