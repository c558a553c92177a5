#pragma once
// Helpers shared by the procedural demo characters: a skeleton from bone
// head/tail positions, and channels sampled from functions of time.
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/rig/character.h"

namespace animorph {

struct BoneSpec {
  std::string name;
  int parent = -1;  // index into the bone list, -1 for a root bone
  glm::vec3 head{0.0f};  // world position of the joint (bind pose)
  glm::vec3 tail{0.0f};  // world position of the bone's end
};

// Appends one node per bone (rest translation = head relative to the parent's
// head, no rotation), one skin over them with inverse bind matrices, and a
// mesh node drawing meshIndex with that skin. Bones must list parents first.
// Returns the node index of bone 0.
int addSkeleton(Character& c, const std::vector<BoneSpec>& bones, int meshIndex, const std::string& skinName);

// A channel keyed at `keys` evenly spaced times over [0, durationSec]
// (keys + 1 samples, the last equal to the first for a loop) of value(t).
// CubicSpline channels get tangents from central differences of value.
Channel sampledChannel(int node, ChannelPath path, Interpolation interp, float durationSec, int keys,
                       const std::function<glm::vec4(float)>& value);

// Quaternion as a channel value (x, y, z, w).
inline glm::vec4 quatValue(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }

// Four largest entries of weights (per joint), normalised, as joints/weights.
void topFourInfluences(const std::vector<float>& weights, glm::uvec4& joints, glm::vec4& out);

}  // namespace animorph
