#include "core/project/actor_time.h"

#include <cmath>

#include "core/project/animation_end_cache.h"
#include "core/rig/pose.h"

namespace animorph {

double actorClipTimeSec(const Actor& actor, const AnimationClip& clip, double timeSec) {
  return clipTime(clip, (timeSec - actor.timeOffsetSec) * actor.speed, actor.loop);
}

double blobActorTimeSec(const Actor& actor, double timeSec) {
  double t = (timeSec - actor.timeOffsetSec) * actor.speed;
  if (!actor.loop) return t;  // the tree's end matters only to a looping actor
  double end = AnimationEndScope::endSec(actor);
  if (end > 1e-6) {
    t = std::fmod(t, end);
    if (t < 0.0) t += end;
  }
  return t;
}

}  // namespace animorph
