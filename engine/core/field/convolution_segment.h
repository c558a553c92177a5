#pragma once
// Convolution segment with the Cauchy kernel h(r) = 1 / (1 + S^2 r^2)^2
// (McCormack & Sherstyuk 1998; docs/design.md §3): the integral of h over a segment,
// in closed form, with its analytic gradient, the radius -> weight rule, and
// the radius beyond which the weighted contribution stays under eps * T.
#include <cmath>
#include <glm/glm.hpp>

namespace animorph {

// F(x) and grad F(x) for the segment from b along unit direction a, length l,
// kernel sharpness S (1/m). Uses the merged atan2 form. Scalar reference form
// (float or double); the batched kernel in field_kernels.cpp is the fast path.
template <class R>
R convolutionSegmentField(const glm::vec<3, R>& x, const glm::vec<3, R>& b, const glm::vec<3, R>& a, R l, R S,
                          glm::vec<3, R>* gradient = nullptr) {
  glm::vec<3, R> d = x - b;
  R dd = glm::dot(d, d);
  R u = glm::dot(d, a);
  R S2 = S * S;
  R P = R(1) + S2 * (dd - u * u);
  R D = R(1) + S2 * dd;
  R lu = l - u;
  R Q = R(1) + S2 * (dd - R(2) * l * u + l * l);
  if (P < R(1)) P = R(1);  // rounding: the perpendicular distance is never negative
  R p = std::sqrt(P);
  R A = std::atan2(S * l * p, P - S2 * u * lu);
  R F = u / (R(2) * P * D) + lu / (R(2) * P * Q) + A / (R(2) * S * P * p);
  if (gradient) {
    R J0 = lu / (R(4) * P * Q * Q) + u / (R(4) * P * D * D) + R(3) / (R(4) * P) * F;
    *gradient = R(-4) * S2 * J0 * (d - u * a) + a * (R(1) / (D * D) - R(1) / (Q * Q));
  }
  return F;
}

// Weight that puts the surface of a long segment at radius R for threshold T:
// w = 2 S T (1 + S^2 R^2)^(3/2) / pi.
inline double convolutionWeightForRadius(double radius, double S, double threshold) {
  return 2.0 * S * threshold * std::pow(1.0 + S * S * radius * radius, 1.5) / M_PI;
}

// Distance from the segment beyond which w F(x) < eps * T for every x: F is
// largest beside the segment's middle among points at a given distance.
double convolutionCutoffRadius(double length, double S, double weight, double threshold, double eps);

}  // namespace animorph
