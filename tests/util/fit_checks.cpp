#include "util/fit_checks.h"

#include <cmath>

#include <catch2/catch.hpp>

namespace animorph::test {

void checkSameFitUpToScale(const FitReport& a, const FitReport& b, double k) {
  INFO("x1: " << fitSummary(a) << " / " << repairSummary(a));
  INFO("x" << k << ": " << fitSummary(b) << " / " << repairSummary(b));
  CHECK(b.diagonal == Approx(a.diagonal * k).epsilon(1e-4));
  CHECK(b.segments == a.segments);
  CHECK(b.standinComponents == a.standinComponents);
  CHECK(b.meshComponents == a.meshComponents);
  CHECK(b.poor == a.poor);
  CHECK(b.repairs.size() == a.repairs.size());
  CHECK(std::abs(b.farShare - a.farShare) <= 1e-3);
  CHECK(std::abs(b.meanError - a.meanError) <= 1e-3);
  CHECK(b.projection.failures == a.projection.failures);
}

}  // namespace animorph::test
