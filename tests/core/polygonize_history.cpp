// Temporal coherence of the CPU polygoniser: with a PolygonizeHistory, frame after frame gives
// exactly the mesh of a full sweep, and blocks away from what moved are reused; with a tolerance,
// blocks whose field provably moved little are reused too (program_change.h's bounds).
#include <catch2/catch.hpp>

#include <atomic>
#include <algorithm>
#include <cmath>
#include <random>

#include "core/blobtree/compile.h"
#include "core/poly/frame_sequence.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "core/poly/program_change.h"
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

PolygonizeResult run(const FieldProgram& p, PolygonizeHistory* history, bool subBlockLists = true,
                     float toleranceCells = 0.0f) {
  PolygonizeSettings s;
  s.reuseToleranceCells = toleranceCells;
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

namespace {

// Largest distance between corresponding vertices of two meshes with the same vertex count.
double maxDeviation(const TriangleMesh& a, const TriangleMesh& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.positions.size() && i < b.positions.size(); ++i)
    worst = std::max(worst, double(glm::length(a.positions[i] - b.positions[i])));
  return worst;
}

}  // namespace

TEST_CASE("the change bound of each primitive bounds the field's change at any point", "[polygonizer][history]") {
  // Blends, a union, a hyper-blend and an R-union over primitives that move, grow and turn under a frame.
  auto build = [](float k) {
    int id = 1;
    BlobNode frame = makeBlobNode(NodeType::Frame, id++, "frame");
    frame.vec3Param("translation") = Vec3Track(glm::vec3(0.1f * k, -0.05f * k, 0.0f));
    frame.quatParam("rotation") = QuatTrack(glm::angleAxis(0.3f * k, glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f))));
    frame.vec3Param("scale") = Vec3Track(glm::vec3(1.0f + 0.1f * k));
    frame.children.push_back(segmentNode(id++, glm::vec3(0.2f, 0.0f, 0.0f), glm::vec3(0.7f, 0.2f, 0.0f), 0.3f));
    frame.children.push_back(circleNode(id++, glm::vec3(0.3f, 0.3f, 0.1f), glm::vec3(0.0f, 0.0f, 1.0f), 0.2f, 0.15f));
    std::vector<BlobNode> parts;
    parts.push_back(std::move(frame));
    parts.push_back(pointNode(id++, glm::vec3(-0.3f + 0.05f * k, 0.0f, 0.0f), 0.4f + 0.03f * k, 1.0f + 0.2f * k));
    parts.push_back(operatorNode(NodeType::HyperBlend, id++,
                                 {triangleNode(id++, glm::vec3(-0.5f, -0.4f, 0.0f), glm::vec3(-0.1f, -0.5f + 0.04f * k, 0.1f),
                                               glm::vec3(-0.3f, -0.2f, 0.2f), 0.2f),
                                  pointNode(id++, glm::vec3(0.0f, -0.5f, 0.0f), 0.3f)}));
    parts.push_back(operatorNode(NodeType::RUnion, id++,
                                 {pointNode(id++, glm::vec3(0.5f, -0.4f, 0.0f), 0.35f),
                                  segmentNode(id++, glm::vec3(0.4f, -0.6f, 0.0f), glm::vec3(0.8f, -0.5f + 0.06f * k, 0.0f), 0.2f)}));
    parts.push_back(operatorNode(NodeType::Union, id++, {pointNode(id++, glm::vec3(0.0f, 0.6f, 0.0f), 0.3f)}));
    return treeOf(operatorNode(NodeType::Blend, id++, std::move(parts)), 0.5f);
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f);
  FieldEvaluator ev;
  for (float k : {0.01f, 0.1f, 0.5f}) {
    INFO("change " << k);
    FieldProgram prev = compileFieldProgram(build(0.0f), 0.0), now = compileFieldProgram(build(k), 0.0);
    REQUIRE(sameStructure(now, prev));
    std::vector<float> bound = primitiveChangeBounds(now, prev);
    double total = 0.0;
    for (float b : bound) {
      CHECK(std::isfinite(b));
      total += b;
    }
    CHECK(bound.back() == 0.0f);  // the union's point did not change
    double worst = 0.0;
    for (int i = 0; i < 4000; ++i) {
      glm::vec3 x(u(rng), u(rng), 0.5f * u(rng));
      worst = std::max(worst, std::abs(double(ev.evaluatePoint(now, x)) - double(ev.evaluatePoint(prev, x))));
    }
    CHECK(worst > 0.0);
    CHECK(worst <= total * (1.0 + 1e-4) + 1e-6);
  }
}

TEST_CASE("temporal coherence with a tolerance: the full sweep's triangles, vertices within the tolerance, more reuse",
          "[polygonizer][history]") {
  BlobTree tree = scene();
  const float tolerance = 0.1f;
  // Small steps (the arm moves about a hundredth of a cell per frame), then large ones.
  for (double step : {0.0005, 0.05}) {
    INFO("step " << step);
    PolygonizeHistory exact, tolerant;
    size_t reusedExact = 0, reusedTolerant = 0;
    double worst = 0.0, cell = 0.0;
    for (int f = 0; f < 8; ++f) {
      const double t = 0.05 + step * f;
      FieldProgram p = compileFieldProgram(tree, t);
      PolygonizeResult full = run(p, nullptr);
      PolygonizeResult a = run(p, &exact);
      PolygonizeResult withTolerance = run(p, &tolerant, true, tolerance);
      const PolygonizeResult* r = &withTolerance;
      cell = full.stats.cellSize;
      reusedExact += a.stats.blocksReused;
      reusedTolerant += r->stats.blocksReused;
      // The same triangles over the same vertices; every vertex within the tolerance of the full sweep's.
      REQUIRE(r->mesh.positions.size() == full.mesh.positions.size());
      CHECK(r->mesh.indices == full.mesh.indices);
      worst = std::max(worst, maxDeviation(r->mesh, full.mesh));
      MeshTopology topo = analyzeMesh(r->mesh);
      CHECK(topo.manifold());
      CHECK(topo.degenerateTriangles == 0);
      CHECK(r->stats.orphanVertices == 0);
    }
    INFO("reused: exact " << reusedExact << ", with tolerance " << reusedTolerant << "; deviation " << worst / cell
                          << " cells");
    CHECK(worst <= tolerance * cell * 1.001);
    CHECK(reusedTolerant >= reusedExact);
    if (step < 0.001) {
      CHECK(reusedTolerant > reusedExact);  // the slowly moving arm's blocks are kept too
      CHECK(worst > 0.0);                   // and they are the older frame's
    }
  }
}

TEST_CASE("a frame sequence is polygonised on one grid with coherence: watertight frames, a full sweep's triangles",
          "[polygonizer][history]") {
  BlobTree tree = scene();
  const int count = 10;
  auto programOf = [&](int k) { return compileFieldProgram(tree, 0.6 + 0.01 * k); };  // the arm moving slowly
  FrameSequenceSettings fs;
  fs.resolution = 64;
  std::vector<TriangleMesh> meshes(count);
  int calls = 0;
  auto stats = polygonizeFrameSequence(
      count, programOf,
      [&](int k, PolygonizeResult&& r) -> Status {
        CHECK(k == calls++);  // in order
        meshes[size_t(k)] = std::move(r.mesh);
        return {};
      },
      fs);
  INFO(stats.error());
  REQUIRE(stats.ok());
  CHECK(calls == count);
  CHECK_FALSE(stats->cancelled);
  CHECK(stats->blocksReused > 0);
  // The grid holds every frame's own grid, with cells no larger than the finest of them.
  PolygonizeSettings own;
  own.resolution = fs.resolution;
  double worst = 0.0;
  for (int k = 0; k < count; ++k) {
    FieldProgram p = programOf(k);
    auto alone = polygonizeGrid(p, own);
    REQUIRE(alone.ok());
    CHECK(stats->grid.cellSize <= alone->cellSize);
    for (int a = 0; a < 3; ++a) {
      CHECK(stats->grid.origin[a] <= alone->origin[a]);
      CHECK(stats->grid.origin[a] + stats->grid.cellSize * float(stats->grid.cells[a]) >=
            alone->origin[a] + alone->cellSize * float(alone->cells[a]) - 1e-4f);
    }
    PolygonizeSettings same = own;
    same.grid = stats->grid;
    auto full = polygonize(p, same);
    REQUIRE(full.ok());
    REQUIRE(meshes[size_t(k)].positions.size() == full->mesh.positions.size());
    CHECK(meshes[size_t(k)].indices == full->mesh.indices);
    worst = std::max(worst, maxDeviation(meshes[size_t(k)], full->mesh));
    MeshTopology topo = analyzeMesh(meshes[size_t(k)]);
    CHECK(topo.manifold());
    CHECK(topo.components == analyzeMesh(full->mesh).components);
  }
  CHECK(worst <= fs.reuseToleranceCells * stats->grid.cellSize * 1.001);

  // A frame callback's error stops the run and is returned; a set cancel flag returns cancelled.
  auto failed = polygonizeFrameSequence(
      count, programOf, [](int k, PolygonizeResult&&) -> Status { return k == 2 ? Status(Error{"disk full"}) : Status(); }, fs);
  REQUIRE_FALSE(failed.ok());
  CHECK(failed.error().find("disk full") != std::string::npos);
  std::atomic<bool> cancel{true};
  fs.cancel = &cancel;
  auto cancelled = polygonizeFrameSequence(count, programOf, [](int, PolygonizeResult&&) -> Status { return {}; }, fs);
  REQUIRE(cancelled.ok());
  CHECK(cancelled->cancelled);
}
