#include "core/project/actor_time.h"

#include <cmath>

#include "core/blobtree/tree_edit.h"
#include "core/rig/pose.h"

namespace animorph {

double actorClipTimeSec(const Actor& actor, const AnimationClip& clip, double timeSec) {
  return clipTime(clip, (timeSec - actor.timeOffsetSec) * actor.speed, actor.loop);
}

double blobActorTimeSec(const Actor& actor, double timeSec) {
  double t = (timeSec - actor.timeOffsetSec) * actor.speed;
  double end = animationEndSec(actor.blobTree);
  if (actor.loop && end > 1e-6) {
    t = std::fmod(t, end);
    if (t < 0.0) t += end;
  }
  return t;
}

}  // namespace animorph
