#include "scene/morph_scene.h"

#include <algorithm>
#include <cmath>

#include "scene/mesh_character.h"

namespace animorph {

MorphSceneInfo applyMorph(SceneFrame& frame, const MorphRuntime& rt, double timeSec,
                          const MorphFrameSettings& settings, bool implicitStage) {
  MorphSceneInfo info;
  info.stage = morphStageAt(rt.setup, rt.timeline, timeSec, info.progress);
  const std::string& src = rt.setup.sourceActorId;
  const std::string& dst = rt.setup.targetActorId;
  // Which actor's own skinned mesh stays; the other (or both) go.
  const std::string keep = info.stage == MorphStage::Source ? src : info.stage == MorphStage::Target ? dst : "";
  // The skeleton overlay follows the actor whose shape is on screen.
  const std::string bonesOf = info.stage == MorphStage::Collapse  ? src
                              : info.stage == MorphStage::Expand ? dst
                                                                 : keep;
  auto drop = [&](const std::string& id, const std::string& kept) { return (id == src || id == dst) && id != kept; };
  std::erase_if(frame.meshes, [&](const MeshDraw& d) { return drop(d.actorId, keep); });
  std::erase_if(frame.bones, [&](const BoneDraw& b) { return drop(b.actorId, bonesOf); });
  if (!keep.empty() || (info.stage == MorphStage::Morph && !implicitStage)) return info;

  auto out = evaluateMorphFrame(rt, timeSec, settings);
  if (!out) {
    info.error = out.error();
    return info;
  }
  if (out->mesh.positions.empty()) return info;
  MeshDraw d;
  d.actorId = out->actorId.empty() ? src : out->actorId;
  d.character = characterFromMesh(out->mesh, "morph");
  d.meshNode = 0;
  d.meshIndex = 0;
  d.joints = {glm::mat4(1.0f)};
  frame.meshes.push_back(std::move(d));
  return info;
}

std::string describeMorphStage(const MorphSceneInfo& info) {
  std::string s = morphStageName(info.stage);
  if (info.stage == MorphStage::Collapse || info.stage == MorphStage::Morph || info.stage == MorphStage::Expand)
    s += " " + std::to_string(static_cast<int>(std::lround(100.0 * info.progress))) + "%";
  if (!info.error.empty()) s += " (error: " + info.error + ")";
  return s;
}

std::shared_ptr<const MorphRuntime> MorphCache::get(const Project& project, const std::string& baseDir,
                                                    AssetCache& assets, const void* owner, uint64_t revision) {
  if (!project.morph.enabled()) {
    runtime_.reset();
    error_.clear();
    owner_ = nullptr;
    return nullptr;
  }
  if (owner == owner_ && revision == revision_ && (runtime_ || !error_.empty())) return runtime_;
  owner_ = owner;
  revision_ = revision;
  auto r = prepareMorph(project, baseDir, assets);
  if (r) {
    runtime_ = *r;
    error_.clear();
  } else {
    runtime_.reset();
    error_ = r.error();
  }
  return runtime_;
}

}  // namespace animorph
