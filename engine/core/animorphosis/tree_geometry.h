#pragma once
// Where the parts of a BlobTree are: the skeleton points of each sub-tree
// (vector parameters and control points of its primitives, carried through its
// Frame nodes; the other warps are ignored), their centroid and their box
// grown by the radii. Used to place null partners and by the automatic
// correspondence.
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "core/blobtree/blob_tree.h"

namespace animorph {

struct NodeExtent {
  glm::vec3 lo{1e30f}, hi{-1e30f};  // box of the skeleton points grown by the radii
  glm::vec3 sum{0.0f};              // sum of the skeleton points
  int count = 0;                    // number of skeleton points (0: empty sub-tree)
  glm::vec3 centroid() const { return count > 0 ? sum / float(count) : glm::vec3(0.0f); }
  glm::vec3 size() const { return count > 0 ? hi - lo : glm::vec3(0.0f); }
  void merge(const NodeExtent& o);
};

// Extent of the sub-tree of n at timeSec, in the space n's parent sees it in.
NodeExtent subtreeExtent(const BlobNode& n, double timeSec);

// Extent of every node's sub-tree in world space, by node id.
std::unordered_map<int, NodeExtent> worldExtents(const BlobTree& tree, double timeSec);

// True for the nodes a chain of single children passes through unchanged for
// matching: a frame, warp, blend, union or hyper-blend with exactly one child.
bool isTransparentLink(const BlobNode& n);

// Extent of every node's sub-tree in pre-order (TreeIndex::ids order), in the
// space inside the tree's root chain: the frames of the root and of the
// transparent nodes under it (isTransparentLink) are not applied, so a tree and
// the same tree placed under a moved, rotated and scaled frame get the same
// extents. `out` is resized to the node count.
void extentsInsideRootChain(const BlobTree& tree, double timeSec, std::vector<NodeExtent>& out);

}  // namespace animorph
