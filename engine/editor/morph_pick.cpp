#include "editor/morph_pick.h"

#include "editor/blob_pick.h"

namespace animorph {

std::optional<ScenePick> pickMorphSurface(const MorphRuntime& rt, double timeSec, const Ray& ray,
                                          const TriangleMesh* implicitMesh, int fallbackResolution) {
  double u = 0.0;
  const MorphStage stage = morphStageAt(rt.setup, rt.timeline, timeSec, u);
  if (stage == MorphStage::Source || stage == MorphStage::Target) return std::nullopt;
  const std::string& owner = stage == MorphStage::Expand ? rt.setup.targetActorId : rt.setup.sourceActorId;
  if (stage == MorphStage::Morph && implicitMesh && !implicitMesh->positions.empty())
    return pickBlobSurface(owner, glm::mat4(1.0f), *implicitMesh, ray);
  MorphFrameSettings fs;
  fs.resolution = fallbackResolution;
  auto frame = evaluateMorphFrame(rt, timeSec, fs);
  if (!frame || frame->mesh.positions.empty()) return std::nullopt;
  return pickBlobSurface(owner, glm::mat4(1.0f), frame->mesh, ray);
}

}  // namespace animorph
