#pragma once
// An actor's own time at a scene time: its clip offset, speed and loop applied. Shared by
// everything that evaluates a project at a time (the scene, the morph runtime, particle
// commands, the CLI), so it sits with the saved model it reads.
#include "core/project/project.h"
#include "core/rig/character.h"

namespace animorph {

// Clip time of actor at scene time timeSec: (t - offset) * speed, looped or clamped to the clip.
double actorClipTimeSec(const Actor& actor, const AnimationClip& clip, double timeSec);

// Tree time of a BlobTree actor at scene time timeSec: (t - offset) * speed,
// wrapped into [0, last key] when the actor loops and its tree is animated.
double blobActorTimeSec(const Actor& actor, double timeSec);

}  // namespace animorph
