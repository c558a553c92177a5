#pragma once
// Small helpers to build BlobTrees in tests.
#include <random>

#include "core/blobtree/blob_tree.h"

namespace animorph::test {

BlobNode pointNode(int id, glm::vec3 center, float radius, float intensity = 1.0f, float stiffness = 3.0f);
BlobNode segmentNode(int id, glm::vec3 a, glm::vec3 b, float radius);
BlobNode convSegmentNode(int id, glm::vec3 a, glm::vec3 b, float radius, float sharpness = 10.0f);
BlobNode triangleNode(int id, glm::vec3 a, glm::vec3 b, glm::vec3 c, float radius);
BlobNode circleNode(int id, glm::vec3 center, glm::vec3 normal, float circleRadius, float radius);
BlobNode operatorNode(NodeType type, int id, std::vector<BlobNode> children);
BlobTree treeOf(BlobNode root, float threshold = 0.5f);

// A random tree of every node type (depth-limited) inside the unit cube
// around the origin; ids from nextId.
BlobNode randomNode(std::mt19937& rng, int depth, int& nextId);

}  // namespace animorph::test
