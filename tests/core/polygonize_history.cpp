// Temporal coherence of the CPU polygoniser: with a PolygonizeHistory, frame after frame gives
// exactly the mesh of a full sweep, and blocks away from what moved are reused.
#include <catch2/catch.hpp>

#include "blobtree/compile.h"
#include "poly/mesh_checks.h"
#include "poly/polygonizer.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// A static row of blobs (a point and a sphere of segments, some under a union, a convolution
// segment) beside an arm under a frame whose translation is animated from t = 0 to t = 1 and still
// after; point radius animated on [0, 0.5].
BlobTree scene() {
  int id = 1;
  std::vector<BlobNode> still;
  for (int i = 0; i < 12; ++i)
    still.push_back(pointNode(id++, glm::vec3(-1.0f + 0.12f * float(i), 0.1f * float(i % 3), 0.0f), 0.3f));
  still.push_back(operatorNode(NodeType::Union, id++,
                               {segmentNode(id++, glm::vec3(-0.9f, -0.5f, 0.0f), glm::vec3(0.2f, -0.5f, 0.1f), 0.25f),
                                triangleNode(id++, glm::vec3(-0.8f, -0.6f, 0.2f), glm::vec3(-0.4f, -0.7f, 0.3f),
                                             glm::vec3(-0.6f, -0.4f, 0.4f), 0.15f)}));
  still.push_back(convSegmentNode(id++, glm::vec3(-0.9f, 0.5f, 0.0f), glm::vec3(-0.3f, 0.6f, 0.0f), 0.12f));
  BlobNode pulse = pointNode(id++, glm::vec3(0.8f, 0.5f, 0.0f), 0.3f);
  pulse.floatParam("radius").setKey(0.0, 0.3f);
  pulse.floatParam("radius").setKey(0.5, 0.42f);
  still.push_back(pulse);
  BlobNode arm = makeBlobNode(NodeType::Frame, id++, "arm");
  arm.vec3Param("translation").setKey(0.0, glm::vec3(0.0f));
  arm.vec3Param("translation").setKey(1.0, glm::vec3(0.0f, 0.35f, 0.1f));
  arm.children.push_back(segmentNode(id++, glm::vec3(0.6f, -0.3f, 0.0f), glm::vec3(1.0f, -0.5f, 0.0f), 0.2f));
  still.push_back(arm);
  return treeOf(operatorNode(NodeType::Blend, id++, std::move(still)), 0.5f);
}

PolygonizeResult run(const FieldProgram& p, PolygonizeHistory* history, bool subBlockLists = true) {
  PolygonizeSettings s;
  s.resolution = 72;
  Bounds b;
  b.add(glm::vec3(-1.6f, -1.2f, -0.8f));
  b.add(glm::vec3(1.6f, 1.4f, 0.8f));
  s.bounds = b;
  s.history = history;
  s.subBlockLists = subBlockLists;
  auto r = polygonize(p, s);
  REQUIRE(r.ok());
  return std::move(*r);
}

void requireSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  REQUIRE(a.triangleCount() > 100);
  CHECK(a.positions == b.positions);
  CHECK(a.normals == b.normals);
  CHECK(a.indices == b.indices);
}

}  // namespace

TEST_CASE("polygonising frame after frame with a history gives the full sweep's mesh and reuses still blocks",
          "[polygonizer][history]") {
  BlobTree tree = scene();
  for (bool lists : {true, false}) {
    INFO("sub-block lists " << lists);
    PolygonizeHistory history;
    size_t reusedWhileMoving = 0, reusedAtRest = 0;
    // Moving (0 .. 1), then at rest (1.2, 1.4: the same program twice).
    for (double t : {0.0, 0.1, 0.2, 0.3, 0.6, 0.9, 1.2, 1.4}) {
      INFO("t " << t);
      FieldProgram p = compileFieldProgram(tree, t);
      PolygonizeResult full = run(p, nullptr, lists);
      PolygonizeResult coherent = run(p, &history, lists);
      requireSameMesh(full.mesh, coherent.mesh);
      CHECK(coherent.stats.blocksCulled == full.stats.blocksCulled);
      CHECK(coherent.stats.blocksEvaluated == full.stats.blocksEvaluated);
      CHECK(full.stats.blocksReused == 0);
      CHECK(analyzeMesh(coherent.mesh).manifold());
      if (t == 0.0) CHECK(coherent.stats.blocksReused == 0);  // nothing to reuse yet
      if (t > 0.0 && t < 1.0) reusedWhileMoving += coherent.stats.blocksReused;
      if (t == 1.4) {
        // The same program as the frame before: every block not culled by its superblock is reused.
        reusedAtRest = coherent.stats.blocksReused;
        CHECK(coherent.stats.pointsEvaluated == 0);
        CHECK(full.stats.pointsEvaluated > 0);
      }
    }
    CHECK(reusedWhileMoving > 0);       // the still blobs, away from the arm and the pulse
    CHECK(reusedAtRest > 0);
  }
}

TEST_CASE("a history is not used across another grid or another structure", "[polygonizer][history]") {
  BlobTree tree = scene();
  PolygonizeHistory history;
  FieldProgram p0 = compileFieldProgram(tree, 1.2);
  (void)run(p0, &history);
  // Another structure: one more blob. A full sweep, the same mesh as without history.
  BlobTree grown = tree;
  grown.root.children.push_back(pointNode(grown.nextId(), glm::vec3(0.0f, -0.9f, 0.3f), 0.3f));
  FieldProgram p1 = compileFieldProgram(grown, 1.2);
  PolygonizeResult r1 = run(p1, &history);
  CHECK(r1.stats.blocksReused == 0);
  requireSameMesh(run(p1, nullptr).mesh, r1.mesh);
  // Another grid (default bounds): a full sweep.
  PolygonizeSettings s;
  s.resolution = 64;
  s.history = &history;
  auto r2 = polygonize(p1, s);
  REQUIRE(r2.ok());
  CHECK(r2->stats.blocksReused == 0);
  s.history = nullptr;
  auto r3 = polygonize(p1, s);
  REQUIRE(r3.ok());
  requireSameMesh(r3->mesh, r2->mesh);
  // After clear(): a full sweep again.
  history.clear();
  CHECK(run(p1, &history).stats.blocksReused == 0);
  CHECK(run(p1, &history).stats.blocksReused > 0);
}
