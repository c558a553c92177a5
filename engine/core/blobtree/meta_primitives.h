#pragma once
// Expansion of the meta-primitives at one time: spline-of-nodes gives one
// affine frame per copy of its child; a Coons patch gives triangles. Shared by
// the FieldProgram compiler and the reference evaluator in the tests.
#include <array>
#include <vector>

#include "core/blobtree/blob_tree.h"
#include "core/field/space_map.h"

namespace animorph {

// Control points of a Vec3List parameter at time t.
std::vector<glm::vec3> evaluatePoints(const ControlPoints& pts, double timeSec);
void evaluatePoints(const ControlPoints& pts, double timeSec, std::vector<glm::vec3>& out);

// Memory the expansions below reuse when called again (a compiler keeps one): once warm, expanding
// allocates nothing. Results are those of the allocating versions.
struct MetaScratch {
  std::vector<glm::vec3> points[4];
  std::vector<glm::vec3> samples[4];
  std::vector<glm::vec3> grid;
};

// Frames of the copies of a SplineOfNodes node's child: copy i sits at
// C(s_i), s_i = i / (count - 1), its +Z turned along the tangent, scaled
// from scaleStart to scaleEnd.
std::vector<SpaceMap> splineOfNodesFrames(const BlobNode& node, double timeSec);
void splineOfNodesFrames(const BlobNode& node, double timeSec, MetaScratch& scratch, std::vector<SpaceMap>& out);
// The same from the parameters' values (points, count, scaleStart, scaleEnd as evaluated).
void splineOfNodesFrames(const std::vector<glm::vec3>& points, float count, float scaleStart, float scaleEnd,
                         std::vector<SpaceMap>& out);

// Triangles of a CoonsPatch node: the bilinearly blended Coons surface of its
// four boundary curves sampled on a resolution x resolution grid.
std::vector<std::array<glm::vec3, 3>> coonsPatchTriangles(const BlobNode& node, double timeSec);
void coonsPatchTriangles(const BlobNode& node, double timeSec, MetaScratch& scratch,
                         std::vector<std::array<glm::vec3, 3>>& out);
// The same from the parameters' values (its four curves' points and resolution as evaluated);
// uses scratch.samples and scratch.grid only.
void coonsPatchTriangles(const std::vector<glm::vec3>& bottom, const std::vector<glm::vec3>& top,
                         const std::vector<glm::vec3>& left, const std::vector<glm::vec3>& right, float resolution,
                         MetaScratch& scratch, std::vector<std::array<glm::vec3, 3>>& out);

}  // namespace animorph
