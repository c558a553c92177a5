#include "core/paint/paint_mesh.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/rig/skinning.h"

namespace animorph {

PaintMesh paintMeshFromFrame(const SceneFrame& frame, const std::string& actorId) {
  PaintMesh out;
  out.actorId = actorId;
  std::vector<glm::vec3> pos, nrm;
  const Character* character = nullptr;
  for (const MeshDraw& d : frame.meshes) {
    if (d.actorId != actorId || !d.character) continue;
    character = d.character.get();
    const Mesh& mesh = d.character->meshes[d.meshIndex];
    skinMesh(mesh, d.joints, pos, nrm, d.morphWeights);
    const auto base = static_cast<uint32_t>(out.positions.size());
    const glm::mat3 normalM = glm::transpose(glm::inverse(glm::mat3(d.model)));
    for (size_t i = 0; i < pos.size(); ++i) {
      out.positions.push_back(glm::vec3(d.model * glm::vec4(pos[i], 1.0f)));
      glm::vec3 n = i < nrm.size() ? normalM * nrm[i] : glm::vec3(0.0f);
      float len = glm::length(n);
      out.normals.push_back(len > 0.0f ? n / len : glm::vec3(0.0f));
    }
    for (uint32_t idx : mesh.indices) out.indices.push_back(base + idx);
  }
  if (character) out.restLocal = skinnedWorldPositions(*character, nullptr, 0.0f);
  if (out.restLocal.size() != out.positions.size()) out.restLocal.clear();  // not the whole character
  return out;
}

void isolateForPainting(SceneFrame& frame, const MorphSetup& morph, const std::string& actorId) {
  auto hidden = [&](const std::string& id) {
    return id != actorId && (id == morph.sourceActorId || id == morph.targetActorId);
  };
  std::erase_if(frame.meshes, [&](const MeshDraw& d) { return hidden(d.actorId); });
  std::erase_if(frame.bones, [&](const BoneDraw& b) { return hidden(b.actorId); });
}

std::vector<std::vector<uint32_t>> vertexNeighbours(size_t vertexCount, const std::vector<uint32_t>& indices) {
  std::vector<std::vector<uint32_t>> nb(vertexCount);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3];
      if (a >= vertexCount || b >= vertexCount || a == b) continue;
      nb[a].push_back(b);
      nb[b].push_back(a);
    }
  }
  for (auto& n : nb) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return nb;
}

std::vector<int32_t> mirrorVertexMap(const std::vector<glm::vec3>& restLocal, float toleranceM) {
  std::vector<int32_t> out(restLocal.size(), -1);
  if (restLocal.empty() || !(toleranceM > 0.0f)) return out;
  const float cell = toleranceM;
  auto key = [&](const glm::ivec3& c) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(c.x) & 0x1FFFFF) << 42) |
           (static_cast<uint64_t>(static_cast<uint32_t>(c.y) & 0x1FFFFF) << 21) |
           static_cast<uint64_t>(static_cast<uint32_t>(c.z) & 0x1FFFFF);
  };
  auto cellOf = [&](const glm::vec3& p) { return glm::ivec3(glm::floor(p / cell)); };
  std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
  for (size_t i = 0; i < restLocal.size(); ++i) grid[key(cellOf(restLocal[i]))].push_back(static_cast<uint32_t>(i));
  for (size_t i = 0; i < restLocal.size(); ++i) {
    const glm::vec3 m(-restLocal[i].x, restLocal[i].y, restLocal[i].z);
    const glm::ivec3 c = cellOf(m);
    float best = toleranceM * toleranceM;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == grid.end()) continue;
          for (uint32_t j : it->second) {
            glm::vec3 d = restLocal[j] - m;
            float d2 = glm::dot(d, d);
            if (d2 <= best) {
              best = d2;
              out[i] = static_cast<int32_t>(j);
            }
          }
        }
  }
  return out;
}

}  // namespace animorph
