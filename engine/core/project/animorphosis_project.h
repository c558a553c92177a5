#pragma once
// The project's animorphosis put to work: its checks against the actors, its
// timing (interval, global s, each actor's clip offset / speed / loop) and its
// generic tree.
#include "core/animorphosis/animorphosis_timing.h"
#include "core/animorphosis/generic_tree.h"
#include "core/project/project.h"
#include "core/util/result.h"

namespace animorph {

// Source and target exist, are BlobTree actors and differ; end > start; the
// global s is a valid s curve; the graph is valid for the two trees. Errors
// start with "animorphosis" and name the actor, link or field.
Status checkAnimorphosis(const Project& p);

// The graph's links that are still valid for the actors' trees as they are now
// (an edit of a tree may delete or move a linked node): all of them when the
// graph is valid, else those that keep it valid, taken in order.
CorrespondenceGraph stillValidLinks(const Project& p);

// Interval and s of the setup; clip timings from the actors (loop period: the
// tree's last key time when the actor loops).
AnimorphosisTiming animorphosisTiming(const Project& p);

// Where C stands at global s: the source's and the target's transforms blended
// (translation and scale linearly, rotation by slerp).
Transform blendedTransform(const Transform& source, const Transform& target, float s);

// checkAnimorphosis, then buildGenericTree with null-partner anchors measured
// at each actor's clip time at the start of the interval.
Result<GenericTree> projectGenericTree(const Project& p);

}  // namespace animorph
