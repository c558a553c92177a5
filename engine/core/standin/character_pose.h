#pragma once
// A character's vertices at one pose, concatenated over Character::meshNodes()
// (the vertex order of weight maps and stand-in bindings), with each vertex's
// skinning matrix and dominant node, for fitting and projection.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/rig/character.h"

namespace animorph {

struct CharacterPose {
  std::vector<glm::mat4> globals;         // node world matrices (without root)
  std::vector<int> meshNodes;             // Character::meshNodes()
  std::vector<size_t> firstVertex;        // per mesh node, into the arrays below; plus the total at the end
  std::vector<glm::vec3> positions;       // posed, in root space
  std::vector<glm::vec3> normals;         // posed, unit
  std::vector<glm::mat4> vertexMatrices;  // root * global(meshNode) * sum_j w_ij M_j: bind mesh space -> root space
  std::vector<int> dominantNode;          // node of the largest skin weight, or the mesh node when unskinned
  // The blend shapes' bind-space offset of every vertex at this pose (rig/pose.h
  // morphWeightsAt; positions include it); empty when no mesh has an active target.
  std::vector<glm::vec3> morphOffsets;
};

// The blended skinning matrix of vertex v (same operations and order as rig/skinning.h skinMesh).
glm::mat4 vertexSkinMatrix(const Mesh& mesh, size_t v, const std::vector<glm::mat4>& jointMats);

// Poses every mesh of c at clipTimeSec of clip (null: rest pose), in root space,
// blend shapes included (the meshes' default weights when clip is null).
CharacterPose poseCharacter(const Character& c, const AnimationClip* clip, float clipTimeSec, const glm::mat4& root);

// Bounds of the posed vertices (clip null: the rest pose) in world units, with
// every node transform and the skinning applied: what the viewport shows.
Bounds poseBounds(const Character& c, const AnimationClip* clip = nullptr, float clipTimeSec = 0.0f);

// Nodes that can carry stand-in segments: every skin joint, and the node of every unskinned mesh.
std::vector<char> rigNodes(const Character& c);

}  // namespace animorph
