#pragma once
// Which points lie inside a closed triangle mesh (or a union of overlapping closed
// shells, such as a character made of several meshes): the winding number along
// three rays per point (+x, +y, +z), each exact for a closed mesh (signed crossings
// with its triangles, buckets of triangles on a grid over the ray's plane). A point
// is inside where at least two of the three rays see a winding of 1 or more, so one
// ray slipping through a crack of an imperfect mesh (real exporters leave some) or
// grazing an edge does not decide alone.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/poly/mesh.h"

namespace animorph {

// One flag per point: 1 inside mesh (triangles counter-clockwise seen from outside),
// 0 outside. An empty mesh: every point outside. Runs on all threads.
std::vector<uint8_t> pointsInsideMesh(const std::vector<glm::vec3>& points, const TriangleMesh& mesh);

}  // namespace animorph
