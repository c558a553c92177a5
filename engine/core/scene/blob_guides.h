#pragma once
// Where a BlobTree's nodes are in the world at a time: the space of a node's
// parameters (for gizmos) and a line drawing of the skeletons (the viewport's
// "Skeleton" overlay: segments as lines, points and centres as markers,
// frames as small axes).
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/blobtree/blob_tree.h"
#include "core/field/space_map.h"

namespace animorph {

// The map from a node's parameter space to the world: the node's ancestor
// space maps (frames, warps; the first copy of a spline-of-nodes), then the
// actor's transform.
struct NodeSpace {
  glm::mat4 actor{1.0f};
  std::vector<SpaceMap> maps;  // outermost first
  // World position of a point given in the node's parameter space.
  glm::vec3 toWorld(const glm::vec3& local) const;
  // d(world)/d(local) at local (central differences; exact for affine chains).
  glm::mat3 jacobian(const glm::vec3& local) const;
};

// The parameter space of node id at timeSec; false when the node is not in the tree.
bool nodeSpace(const BlobTree& tree, int id, double timeSec, const glm::mat4& actor, NodeSpace& out);

struct BlobGuideLine {
  glm::vec3 a{0.0f}, b{0.0f};
  int node = -1;
};
struct BlobGuideMarker {
  glm::vec3 position{0.0f};
  int node = -1;
};
// A frame's axes: its origin and the tips of its X, Y and Z axes.
struct BlobGuideAxes {
  glm::vec3 origin{0.0f};
  glm::vec3 tips[3];
  int node = -1;
};

struct BlobGuides {
  std::string actorId;
  std::vector<BlobGuideLine> lines;
  std::vector<BlobGuideMarker> markers;
  std::vector<BlobGuideAxes> axes;
};

// The skeleton drawing of tree at timeSec in world space (actor applied).
// axisLengthM sizes the frame axes. Spline-of-nodes copies beyond the first
// 64 are not drawn.
BlobGuides blobGuides(const BlobTree& tree, double timeSec, const glm::mat4& actor, float axisLengthM = 0.12f);

// The lines, markers and axes of guides that belong to top or a node below it.
BlobGuides subtreeGuides(const BlobGuides& guides, const BlobNode& top);

// subtreeGuides(blobGuides(tree, ...), node nodeId) without drawing the rest of the tree: only the
// spaces of the node's ancestors are evaluated (a node hovered in a tree of thousands). Empty
// when nodeId is not in the tree.
BlobGuides blobSubtreeGuides(const BlobTree& tree, int nodeId, double timeSec, const glm::mat4& actor,
                             float axisLengthM = 0.12f);

}  // namespace animorph
