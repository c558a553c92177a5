#pragma once
// Topological checks on triangle meshes shared by tests.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace animorph::test {

struct Topology {
  size_t vertices = 0, edges = 0, faces = 0;
  size_t boundaryOrNonManifoldEdges = 0;  // edges not shared by exactly two faces
  size_t inconsistentEdges = 0;           // shared edges traversed in the same direction twice
  size_t components = 0;
  long eulerCharacteristic() const { return long(vertices) - long(edges) + long(faces); }
  // Genus of a closed orientable surface with one component.
  long genus() const { return (2 - eulerCharacteristic()) / 2; }
};

// Topology of the mesh after welding vertices with identical positions.
Topology weldedTopology(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices);

}  // namespace animorph::test
