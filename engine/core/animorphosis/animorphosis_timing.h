#pragma once
// When an animorphosis happens and how its two animations play through it:
// the interval [startSec, endSec] of the timeline, u = (t - start) / (end -
// start), the global s(u), and each actor's clip timing (both keep playing).
#include "core/anim/track.h"
#include "core/animorphosis/correspondence.h"

namespace animorph {

struct ClipTiming {
  double offsetSec = 0.0;  // timeline time at which the clip's time 0 plays
  double speed = 1.0;      // clip seconds per timeline second (> 0)
  double loopSec = 0.0;    // > 0: the clip repeats with this period
  // Clip time at timeline time t.
  double localTime(double timeSec) const;
};

struct AnimorphosisTiming {
  double startSec = 0.0;  // t0: before it A plays
  double endSec = 1.0;    // t1 > t0: after it B plays
  FloatTrack globalS = defaultSCurve();
  ClipTiming source;
  ClipTiming target;
  double u(double timeSec) const { return (timeSec - startSec) / (endSec - startSec); }
};

}  // namespace animorph
