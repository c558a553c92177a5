#pragma once
// Showing a project's morph in an evaluated scene: before A only the source
// actor, after D only the target, in between the morph's output mesh (the
// transitioned skin, or the polygonised implicit morph) in their place.
#include <memory>
#include <string>

#include "core/project/project.h"
#include "core/scene/morph_runtime.h"
#include "core/scene/scene_frame.h"

namespace animorph {

struct MorphSceneInfo {
  MorphStage stage = MorphStage::Source;
  double progress = 0.0;  // within the stage, 0..1
  std::string error;      // evaluation failed (the actors are shown as they are)
  // The implicit surface's share of the picture: 1 in B..C, the cross-fade's
  // ramp within its window around B and C, else 0; and the morph progress u
  // it is shown at (0 just before B, 1 just after C). A caller drawing the
  // surface itself (implicitStage false) draws it at this opacity.
  double implicitOpacity = 0.0;
  double implicitProgress = 0.0;
  // Collapse / expansion: the implicit surface is the transition's stand-in
  // core (scene/standin_core.h) at transition progress implicitProgress, drawn
  // opaque with the mesh (implicitOpacity 1).
  bool implicitCore = false;
};

// Replaces the source and target actors of frame by the morph at timeSec:
// the transitioned mesh (collapse, expansion) or the polygonised implicit
// morph, both (with complementary opacity) within the cross-fade window
// around B and C when the setup enables it; with the transitions, their
// stand-in core while it lasts (settings.standinCore). Transitions are CPU meshes.
// implicitStage false: no implicit surface is added (the caller draws it from
// a preview, scene/morph_preview_source.h, at info.implicitOpacity).
MorphSceneInfo applyMorph(SceneFrame& frame, const MorphRuntime& rt, double timeSec,
                          const MorphFrameSettings& settings, bool implicitStage = true);

// The same; with settings.gpuTransitions the transitions become
// frame.transitions (deformed in the vertex shader; they keep rt alive).
MorphSceneInfo applyMorph(SceneFrame& frame, const std::shared_ptr<const MorphRuntime>& rt, double timeSec,
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
