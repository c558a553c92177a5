#include "core/animorphosis/animorphosis_timing.h"

#include <cmath>

namespace animorph {

double ClipTiming::localTime(double timeSec) const {
  double t = (timeSec - offsetSec) * speed;
  if (loopSec > 0.0) {
    t = std::fmod(t, loopSec);
    if (t < 0.0) t += loopSec;
  }
  return t;
}

}  // namespace animorph
