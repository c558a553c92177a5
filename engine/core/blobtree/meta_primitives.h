#pragma once
// Expansion of the meta-primitives at one time: spline-of-nodes gives one
// affine frame per copy of its child; a Coons patch gives triangles. Shared by
// the FieldProgram compiler and the reference evaluator in the tests.
#include <array>
#include <vector>

#include "blobtree/blob_tree.h"
#include "field/space_map.h"

namespace animorph {

// Control points of a Vec3List parameter at time t.
std::vector<glm::vec3> evaluatePoints(const ControlPoints& pts, double timeSec);

// Frames of the copies of a SplineOfNodes node's child: copy i sits at
// C(s_i), s_i = i / (count - 1), its +Z turned along the tangent, scaled
// from scaleStart to scaleEnd.
std::vector<SpaceMap> splineOfNodesFrames(const BlobNode& node, double timeSec);

// Triangles of a CoonsPatch node: the bilinearly blended Coons surface of its
// four boundary curves sampled on a resolution x resolution grid.
std::vector<std::array<glm::vec3, 3>> coonsPatchTriangles(const BlobNode& node, double timeSec);

}  // namespace animorph
