// The scrubbing grid of a shape that moves sideways: it keeps the previous grid's lattice (origin
// moved by whole superblocks, extent following the shape) so the CPU polygoniser's history reuses
// the blocks both frames share; a shape that grows past the grid or changes cell size gets its own.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/blobtree/compile.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "core/poly/scrubbing_grid.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;

namespace {

constexpr int kLatticeCells = 32;  // the CPU polygoniser's superblock, in cells

// A seeded still cluster of blobs above the path of two blobs that walk along +x by `walked`
// (world units): the shape's bounds move sideways, the cluster's field stays where it was.
BlobTree walkingShape(uint32_t seed, float walked) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.25f, 0.25f);
  int id = 1;
  std::vector<BlobNode> nodes;
  for (int i = 0; i < 6; ++i)
    nodes.push_back(pointNode(id++, glm::vec3(0.5f * u(rng), 0.9f + 0.4f * u(rng), 3.0f * u(rng)), 0.22f + 0.2f * std::fabs(u(rng))));
  nodes.push_back(pointNode(id++, glm::vec3(-3.0f + walked, 0.0f, 0.0f), 0.3f));
  nodes.push_back(segmentNode(id++, glm::vec3(0.4f + walked, 0.0f, 0.0f), glm::vec3(0.6f + walked, 0.05f, 0.0f), 0.25f));
  return treeOf(operatorNode(NodeType::Blend, id++, std::move(nodes)), 0.5f);
}

PolygonizeResult polygonizeOn(const FieldProgram& p, const PolygonizeGrid& grid, PolygonizeHistory* history,
                              float toleranceCells) {
  PolygonizeSettings s;
  s.grid = grid;
  s.history = history;
  s.reuseToleranceCells = toleranceCells;
  auto r = polygonize(p, s);
  REQUIRE(r.ok());
  return std::move(*r);
}

PolygonizeGrid ownGrid(const FieldProgram& p, int resolution) {
  PolygonizeSettings s;
  s.resolution = resolution;
  auto g = polygonizeGrid(p, s);
  REQUIRE(g.ok());
  REQUIRE(!g->empty);
  return *g;
}

double maxVertexDistance(const TriangleMesh& a, const TriangleMesh& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.positions.size() && i < b.positions.size(); ++i)
    worst = std::max(worst, double(glm::length(a.positions[i] - b.positions[i])));
  return worst;
}

}  // namespace

TEST_CASE("a shape walking 4 cells a frame keeps its grid lattice and reuses blocks, the full sweep's mesh within 0.1 cell",
          "[polygonizer][history][scrubbing]") {
  const float tolerance = 0.1f;
  for (uint32_t seed : {11u, 12u, 13u}) {
    INFO("seed " << seed);
    const PolygonizeGrid first = ownGrid(compileFieldProgram(walkingShape(seed, 0.0f), 0.0), 64);
    const float step = 4.0f * first.cellSize;  // 4 cells a frame
    PolygonizeHistory lattice, contained;      // the new grid hold, the containment-only one (as before)
    size_t reusedLattice = 0, reusedContained = 0;
    int shiftedFrames = 0;
    double worst = 0.0;
    for (int f = 0; f < 11; ++f) {
      const FieldProgram p = compileFieldProgram(walkingShape(seed, step * float(f)), 0.0);
      const PolygonizeGrid own = ownGrid(p, 64);
      const PolygonizeGrid g = scrubbingGrid(own, lattice);
      // One lattice: the first grid's cell, its origin moved by whole superblocks; the shape covered.
      REQUIRE(g.cellSize == first.cellSize);
      for (int a = 0; a < 3; ++a) {
        const double moved = double(g.origin[a] - first.origin[a]) / double(g.cellSize);
        CHECK(std::fabs(moved - double(kLatticeCells) * std::round(moved / kLatticeCells)) < 1e-2);
        CHECK(g.origin[a] <= own.origin[a] + 1e-4f * g.cellSize);  // float rounding of the moved origin
        CHECK(g.origin[a] + g.cellSize * float(g.cells[a]) >= own.origin[a] + own.cellSize * float(own.cells[a]) - 1e-4f);
      }
      if (std::fabs(g.origin.x - first.origin.x) > 0.5f * g.cellSize) ++shiftedFrames;
      const PolygonizeResult r = polygonizeOn(p, g, &lattice, tolerance);
      const PolygonizeResult full = polygonizeOn(p, g, nullptr, 0.0f);
      reusedLattice += r.stats.blocksReused;
      REQUIRE(full.mesh.triangleCount() > 100);
      REQUIRE(r.mesh.positions.size() == full.mesh.positions.size());
      CHECK(r.mesh.indices == full.mesh.indices);
      worst = std::max(worst, maxVertexDistance(r.mesh, full.mesh) / double(g.cellSize));
      CHECK(r.stats.orphanVertices == 0);
      CHECK(analyzeMesh(r.mesh).manifold());
      // Before: the previous grid held only while it contained the shape.
      const PolygonizeGrid held = holdScrubbingGrid(own, contained.grid());
      reusedContained += polygonizeOn(p, held, &contained, tolerance).stats.blocksReused;
    }
    INFO("blocks reused: on the lattice " << reusedLattice << ", containment only " << reusedContained
                                          << "; worst vertex " << worst << " cells; frames with a moved origin "
                                          << shiftedFrames);
    CHECK(shiftedFrames > 0);
    CHECK(reusedContained == 0);
    CHECK(reusedLattice > 0);
    CHECK(worst <= tolerance * 1.001);
  }
}

TEST_CASE("the scrubbing grid is the shape's own when it grows past the grid or its cell size changes",
          "[polygonizer][scrubbing]") {
  PolygonizeGrid previous;
  previous.origin = glm::vec3(-1.0f, -2.0f, 0.5f);
  previous.cellSize = 0.0625f;  // values exact in float
  previous.cells[0] = 64;
  previous.cells[1] = 40;
  previous.cells[2] = 20;
  PolygonizeGrid own = previous;
  own.cells[0] = 60;
  own.origin.x += 0.0625f * 10.0f;  // 10 cells along +x: past the grid's end
  const PolygonizeGrid moved = holdScrubbingGrid(own, previous, 1.25f, kLatticeCells);
  CHECK(moved.cellSize == previous.cellSize);
  CHECK(moved.origin == previous.origin);  // 10 cells: the same superblock step
  CHECK(moved.cells[0] == 70);
  CHECK(moved.cells[1] == 40);
  CHECK(holdScrubbingGrid(own, previous).cells[0] == own.cells[0]);  // no lattice: its own grid, as before
  own.origin.x += 0.0625f * 30.0f;  // 40 cells in all: one superblock step
  const PolygonizeGrid stepped = holdScrubbingGrid(own, previous, 1.25f, kLatticeCells);
  CHECK(stepped.origin.x == previous.origin.x + 0.0625f * 32.0f);
  CHECK(stepped.cells[0] == 68);
  // Grown past the grid: one axis longer than the previous grid's.
  PolygonizeGrid grown = own;
  grown.cells[1] = 41;
  const PolygonizeGrid g1 = holdScrubbingGrid(grown, previous, 1.25f, kLatticeCells);
  CHECK(g1.origin == grown.origin);
  CHECK(g1.cells[1] == 41);
  // Another cell size (the shape got much larger or smaller), moved out of the grid.
  for (float cell : {0.1f, 0.04f}) {  // beyond 1.25x either way
    PolygonizeGrid other = own;
    other.cellSize = cell;
    other.cells[0] = 20;
    const PolygonizeGrid g2 = holdScrubbingGrid(other, previous, 1.25f, kLatticeCells);
    CHECK(g2.cellSize == cell);
    CHECK(g2.origin == other.origin);
  }
}
