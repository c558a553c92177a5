#pragma once
// The volume of a union of closed triangle meshes that may overlap (the
// transition mesh and the stand-in core drawn inside it, scene/standin_core.h):
// the divergence theorem adds overlaps twice, so the union is measured along
// rays instead. Rays run along +x through the centres of a columns x columns
// grid over the meshes' y-z extent; along each ray every shell's winding number
// is exact (signed crossings with its triangles), and a point is inside the
// union where any shell's winding is at least 1. Exact along x, sampled in y
// and z: the error is of the order of the surface area times the column size.
#include <cstddef>
#include <vector>

#include "core/poly/mesh.h"

namespace animorph {

// Shell k of mesh is its triangles [firstTriangle[k], firstTriangle[k + 1])
// (the last runs to the end); firstTriangle empty: one shell. Each shell is
// oriented counter-clockwise seen from outside. 0 for an empty mesh.
double unionVolume(const TriangleMesh& mesh, const std::vector<size_t>& firstTriangle, int columns = 256);

}  // namespace animorph
