#include "gpu/render/weight_overlay_scene.h"

#include <algorithm>

namespace animorph::gpu {

size_t addWeightOverlay(const SceneFrame& frame, const std::string& actorId, std::vector<float>& weights,
                        MeshCache& meshes, Scene& scene) {
  size_t total = 0;
  for (const auto& d : frame.meshes)
    if (d.actorId == actorId && d.character) total += d.character->meshes[d.meshIndex].vertexCount();
  weights.resize(total, 0.0f);
  size_t offset = 0, added = 0;
  for (const auto& d : frame.meshes) {
    if (d.actorId != actorId || !d.character) continue;
    const size_t n = d.character->meshes[d.meshIndex].vertexCount();
    const GpuMesh* gm = meshes.get(d.character, d.meshIndex);
    if (gm) {
      // The shaded draw of the same mesh and pose goes: the overlay takes its place.
      std::erase_if(scene.meshes, [&](const MeshDraw& m) { return m.mesh == gm && m.model == d.model; });
      WeightOverlayDraw w;
      w.mesh = gm;
      w.model = d.model;
      w.jointMatrices = d.joints;
      w.morphWeights = d.morphWeights;
      w.weights = std::span<const float>(weights.data() + offset, n);
      scene.weightOverlays.push_back(w);
      ++added;
    }
    offset += n;
  }
  return added;
}

}  // namespace animorph::gpu
