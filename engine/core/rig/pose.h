#pragma once
// Evaluating a character at a time: clip sampling, node globals, joint matrices.
#include <span>
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

// Morph target weights of the mesh drawn by meshNode at timeSec of clip: the
// mesh's defaultMorphWeights, replaced by the clip's Weights channel of that node
// where it has one (null clip: the defaults). One weight per morph target of the
// mesh; empty when the node draws no mesh or the mesh has no targets.
std::vector<float> morphWeightsAt(const Character& c, int meshNode, const AnimationClip* clip, float timeSec);

// Whether any weight is non-zero (a mesh whose weights are all zero skips the blend-shape work).
bool hasActiveMorph(std::span<const float> weights);

// Clip time wrapped or clamped to [0, duration].
float clipTime(const AnimationClip& clip, double timeSec, bool loop);

}  // namespace animorph
