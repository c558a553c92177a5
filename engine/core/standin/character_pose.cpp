#include "core/standin/character_pose.h"

#include "core/rig/morph_targets.h"
#include "core/rig/pose.h"

namespace animorph {

glm::mat4 vertexSkinMatrix(const Mesh& mesh, size_t v, const std::vector<glm::mat4>& jointMats) {
  const size_t jointCount = jointMats.size();
  if (mesh.joints0.empty()) return jointMats.empty() ? glm::mat4(1.0f) : jointMats[0];
  glm::mat4 m(0.0f);
  auto accumulate = [&](const glm::uvec4& j, const glm::vec4& w) {
    for (int k = 0; k < 4; ++k)
      if (w[k] != 0.0f && j[k] < jointCount) m += w[k] * jointMats[j[k]];
  };
  accumulate(mesh.joints0[v], mesh.weights0[v]);
  if (!mesh.joints1.empty()) accumulate(mesh.joints1[v], mesh.weights1[v]);
  return m;
}

CharacterPose poseCharacter(const Character& c, const AnimationClip* clip, float clipTimeSec, const glm::mat4& root) {
  CharacterPose out;
  out.globals = poseGlobals(c, clip, clipTimeSec);
  out.meshNodes = c.meshNodes();
  size_t total = 0;
  for (int node : out.meshNodes) {
    out.firstVertex.push_back(total);
    total += c.meshes[size_t(c.nodes[size_t(node)].mesh)].vertexCount();
  }
  out.firstVertex.push_back(total);
  out.positions.resize(total);
  out.normals.resize(total);
  out.vertexMatrices.resize(total);
  out.dominantNode.resize(total);
  for (size_t k = 0; k < out.meshNodes.size(); ++k) {
    const int node = out.meshNodes[k];
    const Node& n = c.nodes[size_t(node)];
    const Mesh& mesh = c.meshes[size_t(n.mesh)];
    const auto joints = jointMatrices(c, node, out.globals);
    const glm::mat4 model = root * out.globals[size_t(node)];
    const Skin* skin = n.skin >= 0 ? &c.skins[size_t(n.skin)] : nullptr;
    std::vector<glm::vec3> morphedP, morphedN;
    const std::vector<float> weights = morphWeightsAt(c, node, clip, clipTimeSec);
    const bool morphed = hasActiveMorph(weights);
    if (morphed) {
      morphMesh(mesh, weights, morphedP, morphedN);
      if (out.morphOffsets.empty()) out.morphOffsets.assign(total, glm::vec3(0.0f));
    }
    const std::vector<glm::vec3>& P = morphed ? morphedP : mesh.positions;
    const std::vector<glm::vec3>& N = morphed ? morphedN : mesh.normals;
    for (size_t v = 0; v < mesh.vertexCount(); ++v) {
      const size_t i = out.firstVertex[k] + v;
      const glm::mat4 w = model * vertexSkinMatrix(mesh, v, joints);
      out.vertexMatrices[i] = w;
      out.positions[i] = glm::vec3(w * glm::vec4(P[v], 1.0f));
      if (morphed) out.morphOffsets[i] = P[v] - mesh.positions[v];
      glm::vec3 nrm = v < N.size() ? N[v] : glm::vec3(0, 1, 0);
      nrm = glm::transpose(glm::inverse(glm::mat3(w))) * nrm;
      const float len = glm::length(nrm);
      out.normals[i] = len > 0.0f ? nrm / len : glm::vec3(0, 1, 0);
      int dom = node;
      if (skin && !mesh.joints0.empty()) {
        float best = -1.0f;
        auto consider = [&](const glm::uvec4& j, const glm::vec4& wt) {
          for (int q = 0; q < 4; ++q)
            if (wt[q] > best && j[q] < skin->joints.size()) {
              best = wt[q];
              dom = skin->joints[j[q]];
            }
        };
        consider(mesh.joints0[v], mesh.weights0[v]);
        if (!mesh.joints1.empty()) consider(mesh.joints1[v], mesh.weights1[v]);
      }
      out.dominantNode[i] = dom;
    }
  }
  return out;
}

Bounds poseBounds(const Character& c, const AnimationClip* clip, float clipTimeSec) {
  Bounds b;
  for (const auto& p : poseCharacter(c, clip, clipTimeSec, glm::mat4(1.0f)).positions) b.add(p);
  return b;
}

std::vector<char> rigNodes(const Character& c) {
  std::vector<char> out(c.nodes.size(), 0);
  for (const Skin& s : c.skins)
    for (int j : s.joints)
      if (j >= 0 && j < static_cast<int>(out.size())) out[size_t(j)] = 1;
  for (int node : c.meshNodes())
    if (c.nodes[size_t(node)].skin < 0) out[size_t(node)] = 1;
  return out;
}

}  // namespace animorph
