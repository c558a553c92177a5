#pragma once
// Blend shapes (glTF morph targets) on the CPU: the bind-space mesh a set of
// weights makes, before skinning (rig/skinning.h applies it; the vertex shaders
// do the same on the GPU: shaders/include/morph_targets.glsl).
#include <span>
#include <string>
#include <vector>

#include "core/rig/character.h"

namespace animorph {

// Bind-space positions and normals of mesh under weights (one per morph target;
// missing weights count as 0, extra ones are ignored):
// p = p0 + sum_t w_t dp_t, n = normalize(n0 + sum_t w_t dn_t) (n0 where that sum vanishes).
// outNormals gets one entry per mesh normal. Targets are accumulated in order,
// the order the vertex shader uses.
void morphMesh(const Mesh& mesh, std::span<const float> weights, std::vector<glm::vec3>& outPositions,
               std::vector<glm::vec3>& outNormals);

// Checks that every target of mesh has one position delta per vertex, normal
// deltas that are empty or one per vertex, finite values, and that
// defaultMorphWeights is empty or one per target. Returns "" or the first
// problem, naming the target: "morph target 1 'smile': 12 position deltas for 40 vertices".
std::string checkMorphTargets(const Mesh& mesh);

}  // namespace animorph
