#include "core/rig/pose.h"

#include <algorithm>
#include <cmath>

namespace animorph {
namespace {

// Index of the key interval containing t, and the fraction within it.
void locate(const std::vector<float>& times, float t, size_t& i, float& u) {
  if (t <= times.front()) { i = 0; u = 0.0f; return; }
  if (t >= times.back()) { i = times.size() - 1; u = 0.0f; return; }
  auto it = std::upper_bound(times.begin(), times.end(), t);
  i = static_cast<size_t>(it - times.begin()) - 1;
  float dt = times[i + 1] - times[i];
  u = dt > 0.0f ? (t - times[i]) / dt : 0.0f;
}

glm::vec4 sampleChannel(const Channel& ch, float t) {
  const auto& T = ch.timesSec;
  size_t i;
  float u;
  locate(T, t, i, u);
  const bool cubic = ch.interpolation == Interpolation::CubicSpline;
  auto value = [&](size_t k) { return cubic ? ch.values[3 * k + 1] : ch.values[k]; };
  if (i + 1 >= T.size() || ch.interpolation == Interpolation::Step || u == 0.0f) return value(i);
  if (ch.interpolation == Interpolation::Linear) {
    if (ch.path == ChannelPath::Rotation) {
      glm::vec4 a = value(i), b = value(i + 1);
      glm::quat qa(a.w, a.x, a.y, a.z), qb(b.w, b.x, b.y, b.z);
      glm::quat q = glm::slerp(qa, glm::dot(qa, qb) < 0.0f ? -qb : qb, u);
      return {q.x, q.y, q.z, q.w};
    }
    return glm::mix(value(i), value(i + 1), u);
  }
  // Cubic Hermite spline, glTF appendix C: tangents are scaled by the interval.
  float dt = T[i + 1] - T[i];
  glm::vec4 p0 = ch.values[3 * i + 1], m0 = ch.values[3 * i + 2] * dt;
  glm::vec4 p1 = ch.values[3 * (i + 1) + 1], m1 = ch.values[3 * (i + 1)] * dt;
  float u2 = u * u, u3 = u2 * u;
  glm::vec4 v = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
  if (ch.path == ChannelPath::Rotation) v = glm::normalize(v);
  return v;
}

// The weights of a Weights channel at t into out (out.size() targets; keys with
// fewer weights leave the rest as they are).
void sampleWeightChannel(const Channel& ch, float t, std::vector<float>& out) {
  const auto& T = ch.timesSec;
  const size_t w = static_cast<size_t>(std::max(ch.weightCount, 0));
  const bool cubic = ch.interpolation == Interpolation::CubicSpline;
  const size_t stride = cubic ? 3 * w : w;
  if (w == 0 || ch.weightValues.size() < stride * T.size()) return;
  const size_t m = std::min(w, out.size());
  size_t i;
  float u;
  locate(T, t, i, u);
  auto value = [&](size_t k, size_t target) { return ch.weightValues[k * stride + (cubic ? w : 0) + target]; };
  if (i + 1 >= T.size() || ch.interpolation == Interpolation::Step || u == 0.0f) {
    for (size_t k = 0; k < m; ++k) out[k] = value(i, k);
    return;
  }
  if (ch.interpolation == Interpolation::Linear) {
    for (size_t k = 0; k < m; ++k) out[k] = value(i, k) + (value(i + 1, k) - value(i, k)) * u;
    return;
  }
  const float dt = T[i + 1] - T[i];
  const float u2 = u * u, u3 = u2 * u;
  for (size_t k = 0; k < m; ++k) {
    const float p0 = value(i, k), m0 = ch.weightValues[i * stride + 2 * w + k] * dt;  // out-tangent of key i
    const float p1 = value(i + 1, k), m1 = ch.weightValues[(i + 1) * stride + k] * dt;  // in-tangent of key i + 1
    out[k] = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
  }
}

}  // namespace

std::vector<float> morphWeightsAt(const Character& c, int meshNode, const AnimationClip* clip, float timeSec) {
  if (meshNode < 0 || meshNode >= static_cast<int>(c.nodes.size())) return {};
  const int mesh = c.nodes[static_cast<size_t>(meshNode)].mesh;
  if (mesh < 0 || mesh >= static_cast<int>(c.meshes.size())) return {};
  const Mesh& m = c.meshes[static_cast<size_t>(mesh)];
  std::vector<float> w(m.morphTargets.size(), 0.0f);
  for (size_t k = 0; k < w.size() && k < m.defaultMorphWeights.size(); ++k) w[k] = m.defaultMorphWeights[k];
  if (!clip || w.empty()) return w;
  for (const auto& ch : clip->channels)
    if (ch.path == ChannelPath::Weights && ch.node == meshNode && !ch.timesSec.empty()) sampleWeightChannel(ch, timeSec, w);
  return w;
}

bool hasActiveMorph(std::span<const float> weights) {
  for (float w : weights)
    if (w != 0.0f) return true;
  return false;
}

float clipTime(const AnimationClip& clip, double timeSec, bool loop) {
  double d = clip.durationSec;
  if (d <= 0.0) return 0.0f;
  if (loop) {
    double t = std::fmod(timeSec, d);
    if (t < 0) t += d;
    return static_cast<float>(t);
  }
  return static_cast<float>(std::clamp(timeSec, 0.0, d));
}

std::vector<Transform> sampleLocalTransforms(const Character& c, const AnimationClip* clip, float timeSec) {
  std::vector<Transform> locals(c.nodes.size());
  for (size_t n = 0; n < c.nodes.size(); ++n) locals[n] = c.nodes[n].rest;
  if (!clip) return locals;
  for (const auto& ch : clip->channels) {
    if (ch.node < 0 || ch.node >= static_cast<int>(locals.size()) || ch.timesSec.empty()) continue;
    if (ch.path == ChannelPath::Weights) continue;  // morphWeightsAt
    glm::vec4 v = sampleChannel(ch, timeSec);
    Transform& t = locals[ch.node];
    switch (ch.path) {
      case ChannelPath::Translation: t.translation = glm::vec3(v); break;
      case ChannelPath::Scale: t.scale = glm::vec3(v); break;
      case ChannelPath::Rotation: t.rotation = glm::normalize(glm::quat(v.w, v.x, v.y, v.z)); break;
      case ChannelPath::Weights: break;
    }
  }
  return locals;
}

std::vector<glm::mat4> globalMatrices(const Character& c, const std::vector<Transform>& locals) {
  const size_t n = c.nodes.size();
  std::vector<glm::mat4> globals(n);
  std::vector<char> done(n, 0);
  std::vector<int> chain;
  for (size_t i = 0; i < n; ++i) {
    if (done[i]) continue;
    chain.clear();
    int k = static_cast<int>(i);
    while (k >= 0 && !done[k] && chain.size() <= n) {
      chain.push_back(k);
      k = c.nodes[k].parent;
    }
    glm::mat4 parent = (k >= 0 && done[k]) ? globals[k] : glm::mat4(1.0f);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      parent = parent * locals[*it].matrix();
      globals[*it] = parent;
      done[*it] = 1;
    }
  }
  return globals;
}

std::vector<glm::mat4> poseGlobals(const Character& c, const AnimationClip* clip, float timeSec) {
  return globalMatrices(c, sampleLocalTransforms(c, clip, timeSec));
}

std::vector<glm::mat4> jointMatrices(const Character& c, int meshNode, const std::vector<glm::mat4>& globals) {
  const Node& node = c.nodes[meshNode];
  if (node.skin < 0) return {glm::mat4(1.0f)};
  const Skin& skin = c.skins[node.skin];
  glm::mat4 invMesh = glm::inverse(globals[meshNode]);
  std::vector<glm::mat4> out(skin.joints.size());
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    glm::mat4 ibm = j < skin.inverseBindMatrices.size() ? skin.inverseBindMatrices[j] : glm::mat4(1.0f);
    out[j] = invMesh * globals[skin.joints[j]] * ibm;
  }
  return out;
}

}  // namespace animorph
