#pragma once
// Vertex normals of a triangle mesh.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace animorph {

// Area-weighted vertex normals (sum of the unnormalised face normals around
// each vertex, then normalised). Vertices on no triangle, or whose faces
// cancel out, get (0, 1, 0). Indices must be in range (the importer checks).
std::vector<glm::vec3> computeAreaWeightedNormals(const std::vector<glm::vec3>& positions,
                                                  const std::vector<uint32_t>& indices);

}  // namespace animorph
