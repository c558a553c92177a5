#pragma once
// Catch2 checks on stand-in fit reports, shared by the stand-in tests on generated characters and
// on the test characters.
#include "core/standin/fit_quality.h"

namespace animorph::test {

// Catch2 CHECKs that b, the fit of a's character with every length multiplied by k (a change of
// unit), is a's fit up to the scale: diagonal x k, the same segments, pieces, repairs, projection
// failures and poor verdict, the share of far vertices and the mean error (relative to the
// diagonal) within 0.1 %. Both reports are printed when a check fails.
void checkSameFitUpToScale(const FitReport& a, const FitReport& b, double k);

}  // namespace animorph::test
