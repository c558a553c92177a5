#pragma once
// The viewport's work for one frame, after the UI has drawn: the scene at the current time, the
// morph's stages and its implicit preview, the BlobTree previews (GPU or CPU as the preferences and
// the device decide), the selection a click makes, and the gpu::Scene the renderer draws; and the
// status bar's preview line. State that lives across frames (the morph cache, which morph's GPU
// pipelines were compiled) is kept in ViewportFrame.
#include <memory>
#include <string>
#include <vector>

#include "app/editor/editor_gpu.h"
#include "ui/shell/editor_ui.h"
#include "core/scene/animorphosis_scene.h"
#include "editor/morph_preparer.h"
#include "core/scene/morph_scene.h"
#include "editor/particle_view.h"
#include "core/scene/scene_frame.h"

namespace animorph {

struct ViewportFrameResult {
  gpu::PreviewBackend backend;       // BlobTree previews'
  gpu::PreviewBackend morphBackend;  // the morph stage's (its stand-ins decide Auto on CPU devices)
  bool morphStageShown = false;      // the implicit preview is drawn this frame (B..C or a cross-fade)
  bool particlesShown = false;       // some BlobTree is drawn as particles (it turns into its surface by itself)
};

class ViewportFrame {
 public:
  explicit ViewportFrame(PreviewDevice initialDevice);

  // The morph runtime of the document (prepared off the UI thread once per revision, the previous
  // one shown meanwhile: morph_preparer.h; null without a morph, or while weight painting).
  // Called before the UI draws, so the inspector and the status bar show this frame's morph, and
  // again after, should the UI have edited the document. settle: wait for the preparation (a
  // screenshot is pending).
  void updateMorphRuntime(EditorContext& ectx, const EditorOutput& out, bool settle = false);
  // A morph preparation is running (the frame loop keeps drawing; automation waits for it).
  bool morphPreparing() const { return morphPreparer_.preparing(); }

  // Builds scene for this frame (it points into data kept here until the next call). settle: a screenshot is pending, so the previews compute their
  // refined surfaces now (waiting up to 120 s) instead of in the background.
  ViewportFrameResult build(EditorGpu& gpuSide, EditorUI& ui, EditorContext& ectx, bool settle, gpu::Scene& scene);

  // The frame loop is paced (scene/scrub_pacing.h): the CPU previews get every hardware thread.
  void setScrubPaced(bool paced) { scrubPaced_ = paced; }

  // After a lost device: the new device has compiled no morph pipelines yet.
  void forgetPrewarm() { prewarmedMorph_ = nullptr; }

 private:
  // What the morph shows this frame beside its transitions: the implicit stage's opacity (below 1:
  // the cross-fade, dithered, complementary to the mesh) and whose actor it stands for.
  struct MorphShown {
    float opacity = 0.0f;
    std::string sourceId;
  };
  // build's steps, in order (viewport_frame.cpp says what each does).
  MorphShown applyMorphStage(EditorGpu& g, const Preferences& prefs, EditorContext& ectx, double timeSec, bool settle,
                             int previewThreads, ViewportFrameResult& r);
  std::vector<ParticleDraw> updateBlobPreviews(EditorGpu& g, EditorUI& ui, EditorContext& ectx, bool settle,
                                               int previewThreads, ViewportFrameResult& r);
  void applyClick(EditorGpu& g, EditorContext& ectx, const EditorOutput& out, double timeSec, bool morphStageShown);
  void composeScene(EditorGpu& g, EditorUI& ui, EditorContext& ectx, double timeSec,
                    const std::vector<ParticleDraw>& particles, const MorphShown& morph, const ViewportFrameResult& r,
                    gpu::Scene& scene);

  MorphPreparer morphPreparer_;
  AnimorphosisCache animorphosisCache_;  // the generic tree C of the project's animorphosis
  MorphFrameSettings morphSettings_;             // the transitions; the B->C stage is the implicit preview's
  const MorphRuntime* prewarmedMorph_ = nullptr;  // whose B->C pipelines are compiling or compiled
  PreviewDevice previewDevice_;                   // the preference last seen (a switch retries the GPU)
  bool scrubPaced_ = false;                       // the previous frame paced the loop
  // The scene is drawn from these, alive until the frame is recorded: the gpu::Scene points into them.
  SceneFrame frame_;
  ParticleView particleView_;  // particle systems as markers while their time changes
  std::vector<float> overlayWeights_;
};

}  // namespace animorph
