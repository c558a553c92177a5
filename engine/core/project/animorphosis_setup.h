#pragma once
// The animorphosis of a project (docs/animorphosis.md): which BlobTree actor
// turns into which, over which interval of the timeline, with which global
// s(u) and which correspondence graph. Plain data, saved as the project's
// "animorphosis" section; each actor's clip offset, speed and loop come from
// the actor itself.
#include <string>

#include "core/animorphosis/correspondence.h"

namespace animorph {

struct AnimorphosisSetup {
  std::string sourceActorId;  // a BlobTree actor; empty: no animorphosis
  std::string targetActorId;  // a BlobTree actor
  double startSec = 1.0;      // t0: before it the source plays
  double endSec = 3.0;        // t1 > t0: after it the target plays
  FloatTrack globalS = defaultSCurve();
  CorrespondenceGraph graph;
  bool showGhosts = false;    // the viewport also draws A(t) and B(t) as translucent ghosts within the interval
  bool enabled() const { return !sourceActorId.empty() && !targetActorId.empty(); }
  bool operator==(const AnimorphosisSetup&) const = default;
};

}  // namespace animorph
