#include "core/rig/skinning.h"

#include "core/rig/morph_targets.h"
#include "core/rig/pose.h"

namespace animorph {

void skinMesh(const Mesh& mesh, const std::vector<glm::mat4>& jointMats, std::vector<glm::vec3>& outPositions,
              std::vector<glm::vec3>& outNormals, std::span<const float> morphWeights) {
  const size_t n = mesh.vertexCount();
  const glm::vec3* P = mesh.positions.data();
  const glm::vec3* N = mesh.normals.data();
  std::vector<glm::vec3> morphedP, morphedN;
  if (!mesh.morphTargets.empty() && hasActiveMorph(morphWeights)) {
    morphMesh(mesh, morphWeights, morphedP, morphedN);
    P = morphedP.data();
    N = morphedN.data();
  }
  outPositions.resize(n);
  outNormals.resize(mesh.normals.size());
  const bool hasSecondSet = !mesh.joints1.empty();
  const size_t jointCount = jointMats.size();
  for (size_t v = 0; v < n; ++v) {
    glm::mat4 m(0.0f);
    auto accumulate = [&](const glm::uvec4& j, const glm::vec4& w) {
      for (int k = 0; k < 4; ++k)
        if (w[k] != 0.0f && j[k] < jointCount) m += w[k] * jointMats[j[k]];
    };
    if (mesh.joints0.empty()) {
      m = jointMats.empty() ? glm::mat4(1.0f) : jointMats[0];
    } else {
      accumulate(mesh.joints0[v], mesh.weights0[v]);
      if (hasSecondSet) accumulate(mesh.joints1[v], mesh.weights1[v]);
    }
    outPositions[v] = glm::vec3(m * glm::vec4(P[v], 1.0f));
    if (v < mesh.normals.size()) {
      glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(m)));
      glm::vec3 nrm = nm * N[v];
      float len = glm::length(nrm);
      outNormals[v] = len > 0.0f ? nrm / len : N[v];
    }
  }
}

std::vector<glm::vec3> skinnedWorldPositions(const Character& c, const AnimationClip* clip, float timeSec) {
  auto globals = poseGlobals(c, clip, timeSec);
  std::vector<glm::vec3> out, pos, nrm;
  for (int node : c.meshNodes()) {
    const Mesh& mesh = c.meshes[c.nodes[node].mesh];
    skinMesh(mesh, jointMatrices(c, node, globals), pos, nrm, morphWeightsAt(c, node, clip, timeSec));
    for (const auto& p : pos) out.push_back(glm::vec3(globals[node] * glm::vec4(p, 1.0f)));
  }
  return out;
}

}  // namespace animorph
