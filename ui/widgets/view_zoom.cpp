#include "ui/widgets/view_zoom.h"

#include <cmath>

namespace animorph {

namespace {
constexpr double kWheelStep = 0.85;  // span factor per wheel notch
}

double wheelSpanFactor(float wheelNotches) { return std::pow(kWheelStep, double(wheelNotches)); }

void scaleSpanAround(double& lo, double& hi, double pivot, double factor) {
  lo = pivot - (pivot - lo) * factor;
  hi = pivot + (hi - pivot) * factor;
}

void panSpan(double& lo, double& hi, float deltaPx, float spanPx, bool contentUp) {
  if (spanPx <= 0.0f) return;
  const double d = double(deltaPx) * (hi - lo) / double(spanPx) * (contentUp ? -1.0 : 1.0);
  lo -= d;
  hi -= d;
}

}  // namespace animorph
