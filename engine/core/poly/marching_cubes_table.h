#pragma once
// Marching-cubes case table, generated at start-up by walking the cube's faces
// (after Bloomenthal): on every face the crossing points are joined so that
// each run of inside corners is cut off on its own. The rule depends only on
// the face's own corner signs, so two cells sharing a face always agree
// (watertight). Each loop is fanned from an apex whose diagonals never join two
// edges of one face, so a cell never draws an edge its face neighbour may draw
// too (manifold) and no triangle lies in a face plane (none degenerate).
// Triangles are wound so their normals point outside.
#include <array>
#include <cstdint>

namespace animorph {

// Corner c of a cell sits at (c & 1, (c >> 1) & 1, (c >> 2) & 1).
// Edge e joins corners kEdgeCorners[e][0] -> [1], along axis e / 4.
struct MarchingCubesTable {
  std::array<std::array<uint8_t, 2>, 12> edgeCorners;
  std::array<uint8_t, 12> edgeAxis;
  // For each case (bit c set = corner c inside, f >= 0): triangles as edge
  // triples, terminated by 255. At most 12 triangles per case.
  std::array<std::array<uint8_t, 37>, 256> triangles;
  std::array<uint8_t, 256> triangleCount;
};

const MarchingCubesTable& marchingCubesTable();

}  // namespace animorph
