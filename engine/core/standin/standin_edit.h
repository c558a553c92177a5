#pragma once
// Geometry of hand edits of a stand-in's segments (docs/design.md §4: the artist
// adds, removes, moves, re-radii and rebinds segments): rebinding a segment to
// another node without moving it, and refitting one segment.
#include <vector>

#include <glm/glm.hpp>

#include "core/standin/fit_standin.h"
#include "core/standin/standin.h"
#include "core/util/result.h"

namespace animorph {

// seg bound to newNode with its ends and radius where they are at the pose
// `globals` (rig/pose.h poseGlobals): the ends are carried through the world.
// A node out of range of globals counts as the identity.
StandinSegment rebindSegment(const StandinSegment& seg, int newNode, const std::vector<glm::mat4>& globals);

// seg refitted to c: the stand-in is fitted with settings and the fitted
// segment on seg.node nearest to seg (sum of end distances) replaces it.
// Errors: the fit fails, or the fit puts no segment on that node (it
// dominates no vertex), naming the node.
Result<StandinSegment> refitSegment(const Character& c, const StandinSegment& seg, const FitSettings& settings);

}  // namespace animorph
