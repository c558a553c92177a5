#pragma once
// A demo animated BlobTree creature built in code: a frame hierarchy for the
// body, four legs and the head, a spline-of-nodes tail that sways, and a torso
// whose radius breathes. Loops over 2 seconds.
#include "core/blobtree/blob_tree.h"

namespace animorph {

inline constexpr double kBlobCreatureLoopSec = 2.0;

BlobTree makeBlobCreature();

}  // namespace animorph
