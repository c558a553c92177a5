#pragma once
// Cutting a triangle mesh along the zero level of a value given at its vertices (a
// field, a signed distance): the part where the value is <= 0 is kept, triangles
// crossing the level are cut along it (the crossing on each edge by linear
// interpolation, shared by the triangles on both sides of the edge, so the kept
// part stays connected). Normals and colours are interpolated like the positions.
#include <vector>

#include "core/poly/mesh.h"

namespace animorph {

// Appends the part of mesh where value <= 0 to out (value: one per vertex of mesh).
// Returns how many of mesh's triangles were dropped whole (every vertex above 0).
size_t appendClippedMesh(const TriangleMesh& mesh, const std::vector<float>& value, TriangleMesh& out);

}  // namespace animorph
