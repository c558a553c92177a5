#pragma once
// Showing a project's morph in an evaluated scene: before A only the source
// actor, after D only the target, in between the morph's output mesh (the
// transitioned skin, or the polygonised implicit morph) in their place.
#include <memory>
#include <string>

#include "doc/project.h"
#include "morph/morph_runtime.h"
#include "scene/scene_frame.h"

namespace animorph {

struct MorphSceneInfo {
  MorphStage stage = MorphStage::Source;
  double progress = 0.0;  // within the stage, 0..1
  std::string error;      // evaluation failed (the actors are shown as they are)
};

// Replaces the source and target actors of frame by the morph at timeSec.
// implicitStage false: during B->C the actors go but no mesh is added (the
// caller draws the stage from a preview: scene/morph_preview_source.h).
MorphSceneInfo applyMorph(SceneFrame& frame, const MorphRuntime& rt, double timeSec,
                          const MorphFrameSettings& settings, bool implicitStage = true);

// "collapse 40%", "morph 75%", "source", ...
std::string describeMorphStage(const MorphSceneInfo& info);

// Keeps a prepared morph for one document state: prepareMorph runs again only
// when the project changes (its revision or the document itself).
class MorphCache {
 public:
  // The runtime for project at revision, or null (no morph, or preparation
  // failed: error() says why).
  std::shared_ptr<const MorphRuntime> get(const Project& project, const std::string& baseDir, AssetCache& assets,
                                          const void* owner, uint64_t revision);
  const std::string& error() const { return error_; }

 private:
  std::shared_ptr<const MorphRuntime> runtime_;
  const void* owner_ = nullptr;
  uint64_t revision_ = 0;
  std::string error_;
};

}  // namespace animorph
