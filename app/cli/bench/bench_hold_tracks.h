#pragma once
// A BlobTree frozen but for one part, for the temporal-coherence benches (`bench animorph-demo`,
// `bench gpu-coherence`): the dragon flapping its wings with the body held, the dinosaur moving
// its tail.
#include <string>

#include "core/blobtree/blob_tree.h"

// Every track of tree held at its value at timeSec, except under nodes whose name starts with
// moving (their sub-trees keep their animation).
animorph::BlobTree benchHoldAllBut(const animorph::BlobTree& tree, const std::string& moving, double timeSec);
