#pragma once
// Linear blend skinning on the CPU (the vertex shader does the same on the GPU).
#include <span>
#include <vector>

#include "core/rig/character.h"

namespace animorph {

// Skins mesh with jointMats (from jointMatrices()); outputs positions and
// normals in the mesh node's space. Normals use the inverse-transpose.
// morphWeights (rig/pose.h morphWeightsAt; empty or all zero: none) blends the
// mesh's morph targets in first (rig/morph_targets.h), as glTF orders it.
void skinMesh(const Mesh& mesh, const std::vector<glm::mat4>& jointMats, std::vector<glm::vec3>& outPositions,
              std::vector<glm::vec3>& outNormals, std::span<const float> morphWeights = {});

// World-space positions of every mesh of the character at timeSec of clip
// (null clip: rest pose; both with the meshes' blend shapes at that time),
// concatenated in meshNodes() order.
std::vector<glm::vec3> skinnedWorldPositions(const Character& c, const AnimationClip* clip, float timeSec);

}  // namespace animorph
