#include "demo/rig_builder.h"

#include <algorithm>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

namespace animorph {

int addSkeleton(Character& c, const std::vector<BoneSpec>& bones, int meshIndex, const std::string& skinName) {
  const int first = static_cast<int>(c.nodes.size());
  Skin skin;
  skin.name = skinName;
  for (size_t b = 0; b < bones.size(); ++b) {
    Node n;
    n.name = bones[b].name;
    const int parent = bones[b].parent;
    n.parent = parent < 0 ? -1 : first + parent;
    n.rest.translation = bones[b].head - (parent < 0 ? glm::vec3(0.0f) : bones[parent].head);
    c.nodes.push_back(n);
    const int id = first + static_cast<int>(b);
    if (parent < 0) c.roots.push_back(id);
    else c.nodes[first + parent].children.push_back(id);
    skin.joints.push_back(id);
    skin.inverseBindMatrices.push_back(glm::translate(glm::mat4(1.0f), -bones[b].head));
  }
  skin.skeletonRoot = first;
  c.skins.push_back(skin);
  Node meshNode;
  meshNode.name = c.meshes[meshIndex].name;
  meshNode.mesh = meshIndex;
  meshNode.skin = static_cast<int>(c.skins.size()) - 1;
  c.nodes.push_back(meshNode);
  c.roots.push_back(static_cast<int>(c.nodes.size()) - 1);
  return first;
}

Channel sampledChannel(int node, ChannelPath path, Interpolation interp, float durationSec, int keys,
                       const std::function<glm::vec4(float)>& value) {
  Channel ch;
  ch.node = node;
  ch.path = path;
  ch.interpolation = interp;
  const float dt = durationSec / keys;
  for (int k = 0; k <= keys; ++k) {
    // The last key repeats the first exactly so the loop closes.
    const float t = k == keys ? durationSec : k * dt;
    const glm::vec4 v = value(k == keys ? 0.0f : t);
    ch.timesSec.push_back(t);
    if (interp == Interpolation::CubicSpline) {
      const float h = 1e-3f * durationSec;
      glm::vec4 a = value(t - h), b = value(t + h);
      if (path == ChannelPath::Rotation) {
        if (glm::dot(a, v) < 0.0f) a = -a;
        if (glm::dot(b, v) < 0.0f) b = -b;
      }
      const glm::vec4 tangent = (b - a) / (2.0f * h);
      ch.values.insert(ch.values.end(), {tangent, v, tangent});
    } else {
      ch.values.push_back(v);
    }
  }
  // Keep consecutive rotation keys in the same hemisphere.
  if (path == ChannelPath::Rotation && interp != Interpolation::CubicSpline)
    for (size_t i = 1; i < ch.values.size(); ++i)
      if (glm::dot(ch.values[i], ch.values[i - 1]) < 0.0f) ch.values[i] = -ch.values[i];
  return ch;
}

void topFourInfluences(const std::vector<float>& weights, glm::uvec4& joints, glm::vec4& out) {
  std::vector<uint32_t> order(weights.size());
  std::iota(order.begin(), order.end(), 0u);
  const size_t keep = std::min<size_t>(4, order.size());
  std::partial_sort(order.begin(), order.begin() + keep, order.end(),
                    [&](uint32_t a, uint32_t b) { return weights[a] != weights[b] ? weights[a] > weights[b] : a < b; });
  joints = glm::uvec4(0);
  out = glm::vec4(0.0f);
  float sum = 0.0f;
  for (size_t k = 0; k < keep; ++k) sum += weights[order[k]];
  if (!(sum > 0.0f)) {
    out.x = 1.0f;
    return;
  }
  for (size_t k = 0; k < keep; ++k) {
    if (weights[order[k]] <= 0.0f) continue;
    joints[k] = order[k];
    out[k] = weights[order[k]] / sum;
  }
}

}  // namespace animorph
