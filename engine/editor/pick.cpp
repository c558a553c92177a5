#include "editor/pick.h"

#include "core/rig/skinning.h"

namespace animorph {

std::optional<ScenePick> pickScene(const SceneFrame& frame, const Ray& ray) {
  std::optional<ScenePick> best;
  std::vector<glm::vec3> pos, nrm;
  for (const MeshDraw& d : frame.meshes) {
    const Mesh& mesh = d.character->meshes[d.meshIndex];
    skinMesh(mesh, d.joints, pos, nrm, d.morphWeights);
    for (auto& p : pos) p = glm::vec3(d.model * glm::vec4(p, 1.0f));
    auto hit = pickTriangle(ray, pos, mesh.indices);
    if (hit && (!best || hit->distance < best->distance)) {
      best = ScenePick{d.actorId, d.meshNode, hit->distance, hit->position};
    }
  }
  return best;
}

}  // namespace animorph
