#include "core/rig/morph_targets.h"

#include <algorithm>
#include <cmath>

namespace animorph {

void morphMesh(const Mesh& mesh, std::span<const float> weights, std::vector<glm::vec3>& outPositions,
               std::vector<glm::vec3>& outNormals) {
  const size_t n = mesh.vertexCount();
  outPositions.assign(mesh.positions.begin(), mesh.positions.end());
  outNormals.assign(mesh.normals.begin(), mesh.normals.end());
  bool normalsMoved = false;
  const size_t targets = std::min(weights.size(), mesh.morphTargets.size());
  for (size_t t = 0; t < targets; ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    const MorphTarget& mt = mesh.morphTargets[t];
    const size_t pn = std::min(n, mt.positionDeltas.size());
    for (size_t v = 0; v < pn; ++v) outPositions[v] += w * mt.positionDeltas[v];
    const size_t nn = std::min(outNormals.size(), mt.normalDeltas.size());
    for (size_t v = 0; v < nn; ++v) outNormals[v] += w * mt.normalDeltas[v];
    normalsMoved |= nn > 0;
  }
  if (!normalsMoved) return;
  for (size_t v = 0; v < outNormals.size(); ++v) {
    const float len = glm::length(outNormals[v]);
    outNormals[v] = len > 1e-20f ? outNormals[v] / len : mesh.normals[v];
  }
}

std::string checkMorphTargets(const Mesh& mesh) {
  const size_t n = mesh.vertexCount();
  for (size_t t = 0; t < mesh.morphTargets.size(); ++t) {
    const MorphTarget& mt = mesh.morphTargets[t];
    const std::string label = "morph target " + std::to_string(t) + " '" + mt.name + "': ";
    if (mt.positionDeltas.size() != n)
      return label + std::to_string(mt.positionDeltas.size()) + " position deltas for " + std::to_string(n) + " vertices";
    if (!mt.normalDeltas.empty() && mt.normalDeltas.size() != n)
      return label + std::to_string(mt.normalDeltas.size()) + " normal deltas for " + std::to_string(n) + " vertices";
    for (const auto* deltas : {&mt.positionDeltas, &mt.normalDeltas})
      for (size_t v = 0; v < deltas->size(); ++v)
        if (!std::isfinite((*deltas)[v].x) || !std::isfinite((*deltas)[v].y) || !std::isfinite((*deltas)[v].z))
          return label + "delta of vertex " + std::to_string(v) + " is not finite";
  }
  if (!mesh.defaultMorphWeights.empty() && mesh.defaultMorphWeights.size() != mesh.morphTargets.size())
    return std::to_string(mesh.defaultMorphWeights.size()) + " default weights for " +
           std::to_string(mesh.morphTargets.size()) + " morph targets";
  return {};
}

}  // namespace animorph
