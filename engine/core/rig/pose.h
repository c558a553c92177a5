#pragma once
// Evaluating a character at a time: clip sampling, node globals, joint matrices.
#include <vector>

#include "core/rig/character.h"

namespace animorph {

// Local transforms of every node at timeSec of the clip (rest pose where a
// channel does not drive a property). clip may be null for the rest pose.
std::vector<Transform> sampleLocalTransforms(const Character& c, const AnimationClip* clip, float timeSec);

// World matrices of every node from local transforms (parents before children
// is not assumed; cycles were rejected at import).
std::vector<glm::mat4> globalMatrices(const Character& c, const std::vector<Transform>& locals);

// Shorthand: globals at timeSec of clip.
std::vector<glm::mat4> poseGlobals(const Character& c, const AnimationClip* clip, float timeSec);

// Joint matrices for the mesh drawn by meshNode, in the glTF formulation:
// inverse(global(meshNode)) * global(joint_j) * inverseBind_j, so that
// global(meshNode) * skinned position is in world space. A mesh without a
// skin gets one identity matrix.
std::vector<glm::mat4> jointMatrices(const Character& c, int meshNode, const std::vector<glm::mat4>& globals);

// Clip time wrapped or clamped to [0, duration].
float clipTime(const AnimationClip& clip, double timeSec, bool loop);

}  // namespace animorph
