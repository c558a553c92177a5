#include <catch2/catch.hpp>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "util/blob_builders.h"
#include "core/scene/blob_guides.h"

using namespace animorph;
using namespace animorph::test;

namespace {

bool sameGuides(const BlobGuides& a, const BlobGuides& b) {
  if (a.lines.size() != b.lines.size() || a.markers.size() != b.markers.size() || a.axes.size() != b.axes.size())
    return false;
  for (size_t i = 0; i < a.lines.size(); ++i)
    if (a.lines[i].a != b.lines[i].a || a.lines[i].b != b.lines[i].b || a.lines[i].node != b.lines[i].node) return false;
  for (size_t i = 0; i < a.markers.size(); ++i)
    if (a.markers[i].position != b.markers[i].position || a.markers[i].node != b.markers[i].node) return false;
  for (size_t i = 0; i < a.axes.size(); ++i)
    if (a.axes[i].origin != b.axes[i].origin || a.axes[i].node != b.axes[i].node ||
        a.axes[i].tips[0] != b.axes[i].tips[0] || a.axes[i].tips[2] != b.axes[i].tips[2])
      return false;
  return true;
}

void ids(const BlobNode& n, std::vector<int>& out) {
  out.push_back(n.id);
  for (const BlobNode& c : n.children) ids(c, out);
}

}  // namespace

TEST_CASE("blob guides: a node's sub-tree drawn alone equals its part of the whole tree's drawing",
          "[blobtree][guides]") {
  const glm::mat4 actor = glm::rotate(glm::translate(glm::mat4(1.0f), {0.5f, 0.0f, -1.0f}), 0.7f, {0.0f, 1.0f, 0.0f});
  int splineSubtrees = 0, compared = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    int next = 1;
    BlobTree tree = treeOf(operatorNode(NodeType::Blend, next++, {randomNode(rng, 4, next), randomNode(rng, 4, next)}));
    const double t = 0.37 * seed;
    const BlobGuides whole = blobGuides(tree, t, actor);
    std::vector<int> all;
    ids(tree.root, all);
    for (int id : all) {
      const BlobNode& n = *tree.find(id);
      const BlobGuides expected = subtreeGuides(whole, n);
      const BlobGuides alone = blobSubtreeGuides(tree, id, t, actor);
      INFO("seed " << seed << ", node " << id);
      REQUIRE(sameGuides(alone, expected));
      ++compared;
      if (n.type == NodeType::SplineOfNodes && !n.children.empty() && !expected.markers.empty()) ++splineSubtrees;
    }
  }
  CHECK(compared > 200);
  CHECK(splineSubtrees > 0);  // copies of a spline-of-nodes were part of the comparison
  CHECK(blobSubtreeGuides(treeOf(pointNode(1, {0, 0, 0}, 0.5f)), 99, 0.0, glm::mat4(1.0f)).markers.empty());
}
