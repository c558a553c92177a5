#include "field/convolution_segment.h"

#include <algorithm>

namespace animorph {

namespace {
// Upper bound of F at distance r from a segment of length l. Every segment
// point c(s) is at least max(r, |s - s*| - r) from x (s* the closest), so
// |x - c(s)|^2 >= (r^2 + tau^2 / 4) / 2; integrating the kernel over the whole
// line gives sqrt(2) pi / (S (1 + S^2 r^2 / 2)^(3/2)). Also F <= l h(r).
double fieldUpperBound(double r, double l, double S) {
  double h = 1.0 / std::pow(1.0 + S * S * r * r, 2.0);
  double line = std::sqrt(2.0) * M_PI / (S * std::pow(1.0 + 0.5 * S * S * r * r, 1.5));
  return std::min(l * h, line);
}
}  // namespace

double convolutionCutoffRadius(double length, double S, double weight, double threshold, double eps) {
  double target = eps * threshold;
  if (weight <= 0.0 || target <= 0.0) return weight <= 0.0 ? 0.0 : INFINITY;
  double lo = 0.0, hi = 1.0 / S;
  while (weight * fieldUpperBound(hi, length, S) >= target && hi < 1e6) hi *= 2.0;
  for (int i = 0; i < 60; ++i) {
    double mid = 0.5 * (lo + hi);
    if (weight * fieldUpperBound(mid, length, S) >= target) lo = mid;
    else hi = mid;
  }
  return hi;
}

}  // namespace animorph
