#pragma once
// Polygonisation of an implicit solid by marching tetrahedra. Used by the
// demo generators (the editor's polygoniser lives in poly/); small, exact and
// watertight rather than fast.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/math/bounds.h"

namespace animorph {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
};

// Triangulates the boundary of {x : f(x) > 0} (inside positive) inside box on
// a grid of cubic cells of edge cellSize, each split into six tetrahedra
// around its main diagonal (the Freudenthal split, so neighbouring cells
// agree on shared faces). Vertices on grid edges are shared: the result is
// watertight and manifold when f is non-zero on the box's boundary, with
// triangles wound counter-clockwise seen from outside. Deterministic.
TriangleMesh marchingTetrahedra(const std::function<float(const glm::vec3&)>& f, const Bounds& box, float cellSize);

}  // namespace animorph
