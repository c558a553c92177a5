// Temporal coherence on the GPU polygoniser (GpuPolygonizeSettings::reuseToleranceCells, frames
// prepared against the previous one: GpuPolygonizer::prepare(..., previous)), on lavapipe with
// validation: a held pose reuses every active block and gives exactly a full sweep's mesh; a
// program where every primitive moves by cells reuses none and is exactly a full sweep; where one
// cluster moves a little, the held one is reused exactly and the moved one within the tolerance
// (a full sweep's triangle count, vertices within 0.1 cell). Off (tolerance < 0) keeps nothing.
// The preview's compiles hold the previous frame's grid while a moving shape fits in it, so its
// frames share a grid and reuse blocks (PreviewFieldCompiler, poly/scrubbing_grid.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <unordered_map>
#include <vector>

#include "core/blobtree/compile.h"
#include "gpu_fixture.h"
#include "polygonizer_rig.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/polygonizer/preview_field_compiler.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::gpu;
using namespace animorph::test;

namespace {

// The shared rig with the device's loop limit; run() is its polygonisation read back.
struct CoherenceRig : PolygonizerRig {
  uint64_t limit = GpuPolygonizer::loopLimit(ctx->properties());
  TriangleMesh run(const GpuField& f, const GpuPolygonizeSettings& s, const GpuPreparedFrame* prepared,
                   GpuPolygonizeStats& stats) {
    return polygonizeAndRead(f, s, prepared, stats);
  }
  std::shared_ptr<const GpuPreparedFrame> prepare(const GpuField& f, const GpuPolygonizeSettings& s,
                                                  const GpuPreparedFrame* previous) {
    auto p = GpuPolygonizer::prepare(f, s, limit, previous);
    INFO(p.error());
    REQUIRE(p.ok());
    return *p;
  }
};

// Two clusters of seeded random points (left at x < 0, right at x > 0); the right one moved by
// rightShift, the left by leftShift.
BlobTree clusters(unsigned seed, glm::vec3 leftShift, glm::vec3 rightShift) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.15f, 0.15f);
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  for (int i = 0; i < 24; ++i) {
    const bool left = i < 12;
    const glm::vec3 c = glm::vec3(left ? -0.55f : 0.55f, 0.0f, 0.0f) + glm::vec3(u(rng), u(rng), u(rng));
    root.children.push_back(pointNode(2 + i, c + (left ? leftShift : rightShift), 0.14f));
  }
  return treeOf(root, 0.5f);
}

Bounds box() {
  Bounds b;
  b.add(glm::vec3(-0.85f, -0.4f, -0.4f));  // at 64 cells along x: two superblocks, one per cluster
  b.add(glm::vec3(0.85f, 0.4f, 0.4f));
  return b;
}

void requireIdentical(const TriangleMesh& a, const TriangleMesh& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  REQUIRE(a.indices.size() == b.indices.size());
  CHECK(a.positions == b.positions);
  CHECK(a.indices == b.indices);
}

// Largest distance from a vertex of a to the nearest vertex of b (brute force: small meshes).
float farthest(const TriangleMesh& a, const TriangleMesh& b) {
  float worst = 0.0f;
  for (const glm::vec3& p : a.positions) {
    float best = 1e30f;
    for (const glm::vec3& q : b.positions) best = std::min(best, glm::dot(p - q, p - q));
    worst = std::max(worst, best);
  }
  return std::sqrt(worst);
}

}  // namespace

TEST_CASE("GPU coherence reuses blocks on a held pose and none when everything moves, meshes identical to full sweeps",
          "[gpu][gpupoly][coherence]") {
  CoherenceRig r;
  for (unsigned seed : {5u, 12u}) {
    INFO("seed " << seed);
    const FieldProgram held = compileFieldProgram(clusters(seed, glm::vec3(0.0f), glm::vec3(0.0f)), 0.0);
    const FieldProgram moved = compileFieldProgram(clusters(seed, glm::vec3(0.0f, 0.09f, 0.0f), glm::vec3(0.0f, -0.09f, 0.0f)), 0.0);
    for (auto lists : {GpuPolygonizeSettings::RegionPrograms::Off, GpuPolygonizeSettings::RegionPrograms::On}) {
      INFO("region lists " << (lists == GpuPolygonizeSettings::RegionPrograms::On));
      GpuPolygonizeSettings s;
      s.resolution = 64;
      s.bounds = box();
      s.regionPrograms = lists;
      GpuPolygonizeStats full, first, second, third;
      const TriangleMesh fullHeld = r.run(GpuField::single(held), s, nullptr, full);
      GpuPolygonizeStats fullMovedStats;
      const TriangleMesh fullMoved = r.run(GpuField::single(moved), s, nullptr, fullMovedStats);
      REQUIRE(fullHeld.triangleCount() > 200);
      // Frame 1: nothing to reuse. Frame 2, the same program: every active block reused.
      auto p1 = r.prepare(GpuField::single(held), s, nullptr);
      r.run(GpuField::single(held), s, p1.get(), first);
      CHECK_FALSE(first.coherent);
      CHECK(first.blocksReused == 0);
      auto p2 = r.prepare(GpuField::single(held), s, p1.get());
      CHECK(p2->hasChangeBounds());
      const TriangleMesh again = r.run(GpuField::single(held), s, p2.get(), second);
      CHECK(second.coherent);
      CHECK(second.blocksActive == full.blocksActive);
      CHECK(second.blocksReused == second.blocksActive);
      requireIdentical(again, fullHeld);
      // Frame 3: every primitive moved by ~3 cells. Exact reuse (tolerance 0): nothing reused,
      // exactly the full sweep. (With a tolerance, an active block the surface does not cross
      // whose values stay far from 0 may be kept: it makes no vertex.)
      GpuPolygonizeSettings exact = s;
      exact.reuseToleranceCells = 0.0f;
      auto p3 = r.prepare(GpuField::single(moved), exact, p2.get());
      const TriangleMesh movedMesh = r.run(GpuField::single(moved), exact, p3.get(), third);
      CHECK(third.coherent);
      CHECK(third.blocksReused == 0);
      requireIdentical(movedMesh, fullMoved);
      // Moved back, exact: blocks keep nothing from two frames ago (their values are of frame 3).
      GpuPolygonizeStats fourth;
      auto p4 = r.prepare(GpuField::single(held), exact, p3.get());
      requireIdentical(r.run(GpuField::single(held), exact, p4.get(), fourth), fullHeld);
      CHECK(fourth.blocksReused == 0);
      // Off: nothing kept, nothing reused.
      GpuPolygonizeSettings off = s;
      off.reuseToleranceCells = -1.0f;
      GpuPolygonizeStats fifth;
      auto p5 = r.prepare(GpuField::single(held), off, p4.get());
      CHECK_FALSE(p5->hasChangeBounds());
      requireIdentical(r.run(GpuField::single(held), off, p5.get(), fifth), fullHeld);
      CHECK_FALSE(fifth.coherent);
      CHECK(fifth.blocksReused == 0);
    }
  }
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU coherence: where one cluster moves a little, the held one is reused exactly and the moved one within 0.1 cell",
          "[gpu][gpupoly][coherence]") {
  CoherenceRig r;
  GpuPolygonizeSettings s;
  s.resolution = 64;
  s.bounds = box();
  s.regionPrograms = GpuPolygonizeSettings::RegionPrograms::On;  // per-superblock primitive sets
  const FieldProgram before = compileFieldProgram(clusters(7, glm::vec3(0.0f), glm::vec3(0.0f)), 0.0);
  GpuPolygonizeStats st;
  auto p1 = r.prepare(GpuField::single(before), s, nullptr);
  r.run(GpuField::single(before), s, p1.get(), st);
  auto prev = p1;
  const float h = st.cellSize;
  std::vector<uint32_t> reusedPerFrame;
  // The right cluster drifts by a thousandth of a cell a frame (within the tolerance), then by a
  // twentieth (beyond it soon).
  std::vector<FieldProgram> programs;
  for (int k = 1; k <= 4; ++k) {
    const float step = k <= 2 ? 0.001f * h * float(k) : 0.05f * h * float(k);
    programs.push_back(compileFieldProgram(clusters(7, glm::vec3(0.0f), glm::vec3(step, 0.0f, 0.0f)), 0.0));
  }
  for (size_t k = 0; k < programs.size(); ++k) {
    INFO("frame " << k + 2);
    const GpuField f = GpuField::single(programs[k]);
    GpuPolygonizeSettings exact = s;
    exact.reuseToleranceCells = -1.0f;
    auto p = r.prepare(f, s, prev.get());
    GpuPolygonizeStats reused;
    const TriangleMesh m = r.run(f, s, p.get(), reused);
    CHECK(reused.coherent);
    CHECK(reused.blocksReused > 0);  // the held cluster's blocks at least
    if (k >= 2) CHECK(reused.blocksReused < reused.blocksActive);  // not the moved cluster's
    reusedPerFrame.push_back(reused.blocksReused);
    prev = p;
    // The full sweep of the same program, on a polygoniser keeping nothing (off) -- a second
    // polygoniser, so that this chain of frames goes on.
    CoherenceRig fresh;
    GpuPolygonizeStats fst;
    const TriangleMesh full = fresh.run(f, exact, nullptr, fst);
    CHECK_FALSE(fst.coherent);
    CHECK(fst.blocksReused == 0);
    CHECK(m.triangleCount() == full.triangleCount());
    CHECK(m.positions.size() == full.positions.size());
    CHECK(farthest(m, full) <= 0.1f * h + 1e-6f);
    CHECK(farthest(full, m) <= 0.1f * h + 1e-6f);
    CHECK(fresh.ctx->validationErrorCount() == 0);
  }
  // Within the tolerance, blocks of the moving cluster were reused too.
  CHECK(reusedPerFrame[0] > reusedPerFrame[3]);
  CHECK(r.ctx->validationErrorCount() == 0);
}

namespace {

// Three clusters of seeded random points along x (at -1.2, 0 and +1.2); the outer two moved towards
// the middle by inward (a shape drawing its arms in: its bounds shrink, its grid alone would move).
// 100 blends of two points each: more than kRegionListMinOps ops, so the preview's Auto settings
// use region lists.
BlobTree threeClusters(unsigned seed, float inward) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.15f, 0.15f);
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  int id = 2;
  for (int i = 0; i < 300; ++i) {
    const int cluster = i / 100;  // 0 left, 1 middle, 2 right
    const float x = cluster == 0 ? -1.2f + inward : cluster == 2 ? 1.2f - inward : 0.0f;
    BlobNode pair = makeBlobNode(NodeType::Blend, id++);
    for (int k = 0; k < 2; ++k) pair.children.push_back(pointNode(id++, glm::vec3(x + u(rng), u(rng), u(rng)), 0.1f));
    root.children.push_back(std::move(pair));
  }
  return treeOf(root, 0.5f);
}

// Largest distance from a vertex of a to the nearest vertex of b, through a hash of cells of size h.
float farthestHashed(const TriangleMesh& a, const TriangleMesh& b, float h) {
  auto key = [h](const glm::vec3& p, int dx, int dy, int dz) {
    const int64_t x = int64_t(std::floor(p.x / h)) + dx, y = int64_t(std::floor(p.y / h)) + dy,
                  z = int64_t(std::floor(p.z / h)) + dz;
    return (x * 73856093) ^ (y * 19349663) ^ (z * 83492791);
  };
  std::unordered_map<int64_t, std::vector<glm::vec3>> cells;
  for (const glm::vec3& q : b.positions) cells[key(q, 0, 0, 0)].push_back(q);
  float worst = 0.0f;
  for (const glm::vec3& p : a.positions) {
    float best = 1e30f;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (auto it = cells.find(key(p, dx, dy, dz)); it != cells.end())
            for (const glm::vec3& q : it->second) best = std::min(best, glm::dot(p - q, p - q));
    worst = std::max(worst, best);
  }
  return std::sqrt(worst);
}

}  // namespace

TEST_CASE("GPU preview scrubbing a moving shape holds its grid: two frames share it and reuse blocks, the mesh within "
          "0.1 cell of a full sweep",
          "[gpu][gpupoly][coherence][preview]") {
  CoherenceRig r;
  PreviewFieldCompiler compiler(r.limit);
  const int res = 96;
  for (unsigned seed : {3u, 21u}) {
    INFO("seed " << seed);
    // Frame 1, then the outer clusters a fifth of a cell closer (the editor's compiles, chained).
    auto c1 = compiler.compileHere(blobTreePreviewSource(std::make_shared<const BlobTree>(threeClusters(seed, 0.0f)), 0.0),
                                   res, 0.0);
    REQUIRE(c1->error.empty());
    REQUIRE(c1->field);
    REQUIRE(c1->field->fieldProgram().ops.size() > GpuPolygonizeSettings::kRegionListMinOps);
    REQUIRE(c1->grid);
    const float h = c1->grid->cellSize;
    auto c2 = compiler.compileHere(
        blobTreePreviewSource(std::make_shared<const BlobTree>(threeClusters(seed, 0.2f * h)), 0.0), res, 0.0);
    REQUIRE(c2->error.empty());
    REQUIRE(c2->grid);
    // Alone, frame 2 would be polygonised on another grid (no block could be reused there).
    const GpuField f1 = previewGpuField(*c1->field), f2 = previewGpuField(*c2->field);
    Result<PolygonizeGrid> own2 = GpuPolygonizer::grid(f2, previewGpuSettings(*c2->field, res));
    REQUIRE(own2.ok());
    CHECK(own2->cellSize != c1->grid->cellSize);
    // Held: the same grid as frame 1, and change bounds against it.
    CHECK(c2->grid->origin == c1->grid->origin);
    CHECK(c2->grid->cellSize == c1->grid->cellSize);
    for (int a = 0; a < 3; ++a) CHECK(c2->grid->cells[a] == c1->grid->cells[a]);
    REQUIRE(c2->prepared);
    CHECK(c2->prepared->hasChangeBounds());
    // Recorded in order as the editor does: frame 2 reuses the middle cluster's blocks.
    GpuPolygonizeSettings s1 = previewGpuSettings(*c1->field, res), s2 = previewGpuSettings(*c2->field, res);
    s1.grid = c1->grid;
    s2.grid = c2->grid;
    GpuPolygonizeStats first, second;
    r.run(f1, s1, c1->prepared.get(), first);
    const TriangleMesh m = r.run(f2, s2, c2->prepared.get(), second);
    CHECK(second.coherent);
    CHECK(second.regionLists);
    CHECK(second.blocksReused > 0);
    CHECK(second.blocksReused < second.blocksActive);  // the moved clusters' blocks are evaluated
    // A full sweep of frame 2 on the same grid, keeping nothing, on a polygoniser of its own.
    CoherenceRig fresh;
    GpuPolygonizeSettings off = s2;
    off.reuseToleranceCells = -1.0f;
    GpuPolygonizeStats fst;
    const TriangleMesh full = fresh.run(f2, off, nullptr, fst);
    CHECK(fst.blocksReused == 0);
    REQUIRE(full.triangleCount() > 1000);
    CHECK(m.triangleCount() == full.triangleCount());
    CHECK(farthestHashed(m, full, h) <= 0.1f * h + 1e-6f);
    CHECK(farthestHashed(full, m, h) <= 0.1f * h + 1e-6f);
    CHECK(fresh.ctx->validationErrorCount() == 0);
  }
  CHECK(r.ctx->validationErrorCount() == 0);
}
