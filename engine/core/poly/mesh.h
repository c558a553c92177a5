#pragma once
// Indexed triangle mesh produced by the polygonisers.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace animorph {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // unit, outward (empty when not computed)
  std::vector<uint32_t> indices;    // 3 per triangle, counter-clockwise seen from outside
  std::vector<glm::vec4> colors;    // linear RGBA per vertex (empty when the mesh has none)

  size_t triangleCount() const { return indices.size() / 3; }
  bool operator==(const TriangleMesh&) const = default;
};

}  // namespace animorph
