#pragma once
// The slow, obviously correct BlobTree evaluator the FieldProgram is tested
// against: recursion over the nodes, tracks evaluated at every point, scalar
// formulas in double where they exist, chain rule through every map.
#include <glm/glm.hpp>

#include "core/blobtree/blob_tree.h"

namespace animorph::test {

// f = p_root(x) - T(t) and its gradient; convolution segments are cut to 0
// beyond their eps * T bound exactly as the compiled program does.
float referenceField(const BlobTree& tree, double timeSec, const glm::vec3& x, glm::vec3* gradient = nullptr,
                     float cutoffEpsilon = 1e-3f);

}  // namespace animorph::test
