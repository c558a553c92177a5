#include "core/rig/mesh_normals.h"

namespace animorph {

std::vector<glm::vec3> computeAreaWeightedNormals(const std::vector<glm::vec3>& positions,
                                                  const std::vector<uint32_t>& indices) {
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    // The cross product's length is twice the area: summing it weights by area.
    glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    normals[a] += n;
    normals[b] += n;
    normals[c] += n;
  }
  for (auto& n : normals) {
    float len = glm::length(n);
    n = len > 1e-20f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return normals;
}

}  // namespace animorph
