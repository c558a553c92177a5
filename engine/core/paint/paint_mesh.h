#pragma once
// The mesh a weight brush paints on: one actor's meshes as the viewport shows
// them at one time (CPU-skinned like the vertex shader, under the actor
// transform), concatenated over Character::meshNodes() so vertex i is entry i
// of the actor's weight map.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/scene_frame.h"

namespace animorph {

struct PaintMesh {
  std::string actorId;
  std::vector<glm::vec3> positions;  // world space, posed
  std::vector<glm::vec3> normals;    // world space, unit
  std::vector<uint32_t> indices;     // triangle list over positions
  std::vector<glm::vec3> restLocal;  // actor space, rest pose (for the X mirror)

  size_t vertexCount() const { return positions.size(); }
};

// The posed mesh of actorId in frame (every MeshDraw of that actor, in
// meshNodes() order as evaluateScene emits them). Empty when the actor has no
// mesh in frame.
PaintMesh paintMeshFromFrame(const SceneFrame& frame, const std::string& actorId);

// Weight Paint mode shows the painted actor as itself (skinned, not morphed):
// removes the other morph actor's meshes and bones from frame.
void isolateForPainting(SceneFrame& frame, const MorphSetup& morph, const std::string& actorId);

// Mesh neighbours of every vertex (sharing a triangle edge), sorted, unique.
std::vector<std::vector<uint32_t>> vertexNeighbours(size_t vertexCount, const std::vector<uint32_t>& indices);

// For each vertex, the vertex nearest to its mirror image across the actor's
// local X = 0 plane (restLocal), or -1 when none lies within toleranceM.
std::vector<int32_t> mirrorVertexMap(const std::vector<glm::vec3>& restLocal, float toleranceM);

}  // namespace animorph
