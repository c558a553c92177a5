#include "app/editor/viewport_frame.h"

#include <cstdio>
#include <cstdlib>

#include "core/paint/paint_mesh.h"
#include "core/project/animation_end_cache.h"
#include "core/scene/animorphosis_scene.h"
#include "editor/blob_pick.h"
#include "editor/click_selection.h"
#include "editor/morph_pick.h"
#include "core/scene/morph_preview_source.h"
#include "editor/pick.h"
#include "core/scene/scene_frame.h"
#include "core/scene/standin_guides.h"
#include "gpu/render/particle_spheres.h"
#include "gpu/frame/scene_from_frame.h"
#include "gpu/render/standin_overlay.h"
#include "gpu/render/weight_overlay_scene.h"

namespace animorph {

ViewportFrame::ViewportFrame(PreviewDevice initialDevice) : previewDevice_(initialDevice) {
  // Collapse and expansion run in the vertex shader (ANIMORPH_CPU_TRANSITIONS=1: on the CPU, for comparison).
  morphSettings_.gpuTransitions = !std::getenv("ANIMORPH_CPU_TRANSITIONS");
}

void ViewportFrame::updateMorphRuntime(EditorContext& ectx, const EditorOutput& out, bool settle) {
  Document& doc = *ectx.document;
  // Not while painting: every stroke is a new revision and would bind the vertices again.
  if (out.weightPaintMode) return;
  ectx.morphRuntime = settle ? morphPreparer_.wait(doc.project(), doc.baseDir(), ectx.assets, &doc, doc.revision())
                             : morphPreparer_.update(doc.project(), doc.baseDir(), ectx.assets, &doc, doc.revision());
}

ViewportFrameResult ViewportFrame::build(EditorGpu& g, EditorUI& ui, EditorContext& ectx, bool settle,
                                         gpu::Scene& scene) {
  ViewportFrameResult r;
  const EditorOutput& out = ui.output();
  Document& doc = *ectx.document;
  const double timeSec = doc.project().timeline.currentTimeSec();
  {
    AnimationEndScope ends(doc.project(), &doc, doc.revision());  // each tree walked once per revision
    frame_ = evaluateScene(doc.project(), doc.baseDir(), ectx.assets, timeSec);
  }
  const Preferences& prefs = ui.state().prefs;
  r.backend = gpu::choosePreviewBackend(prefs.previewDevice, g.ctx->deviceType());
  if (prefs.previewDevice != previewDevice_) {  // the user switched: try the GPU again
    previewDevice_ = prefs.previewDevice;
    g.morphPreview->clearGpuFailure();
    g.blobPreviews->clearGpuFailures();
  }
  updateMorphRuntime(ectx, out, settle);
  const int previewThreads = scrubPaced_ ? pacedPreviewThreads() : interactivePreviewThreads();
  r.morphBackend = r.backend;
  MorphShown morph;
  if (out.weightPaintMode) {  // the painted actor as itself, posed, without the morph
    isolateForPainting(frame_, doc.project().morph, out.weightOverlay.actorId);
    ectx.viewportNote.clear();
  } else {
    morph = applyMorphStage(g, prefs, ectx, timeSec, settle, previewThreads, r);
    if (morphPreparer_.preparing())
      ectx.viewportNote += std::string(ectx.viewportNote.empty() ? "" : "  |  ") + "preparing the morph...";
    const std::string note =
        describeAnimorphosis(applyAnimorphosis(frame_, doc.project(), animorphosisCache_, &doc, doc.revision(),
                                               doc.project().animorphosis.showGhosts));
    if (!note.empty()) ectx.viewportNote += (ectx.viewportNote.empty() ? "" : "  |  ") + note;
  }
  const std::vector<ParticleDraw> particles = updateBlobPreviews(g, ui, ectx, settle, previewThreads, r);
  if (out.pick) applyClick(g, ectx, out, timeSec, r.morphStageShown);

  // A screenshot shows the refined implicit surfaces, not whatever is ready.
  if (settle && !g.blobPreviews->waitIdle(120.0))
    std::fprintf(stderr, "animorph: BlobTree preview still computing at the screenshot\n");
  if (settle && r.morphStageShown && !g.morphPreview->waitIdle(120.0))
    std::fprintf(stderr, "animorph: morph preview still computing at the screenshot\n");
  composeScene(g, ui, ectx, timeSec, particles, morph, r, scene);
  return r;
}

// The morph at this frame: its transitions applied to frame_, its implicit stage (B..C, the
// cross-fade's window, the transitions' stand-in core) handed to the morph preview, its pipelines
// prewarmed for a GPU backend.
ViewportFrame::MorphShown ViewportFrame::applyMorphStage(EditorGpu& g, const Preferences& prefs, EditorContext& ectx,
                                                         double timeSec, bool settle, int previewThreads,
                                                         ViewportFrameResult& r) {
  MorphShown shown;
  auto rt = ectx.morphRuntime;
  if (!rt) {
    ectx.viewportNote = morphPreparer_.error().empty() ? "" : "morph: " + morphPreparer_.error();
    return shown;
  }
  // A morph with colours: on CPU devices Auto takes the worker for it (the GPU path's colour pass
  // walks the whole colour program at every vertex, several times slower there: `bench gpu-color`).
  const bool convolution = !rt->source.isTree() && !rt->target.isTree() &&
                           rt->source.morph.standin.kind == StandinKind::Convolution &&
                           rt->target.morph.standin.kind == StandinKind::Convolution && !morphHasColors(*rt);
  r.morphBackend = gpu::choosePreviewBackend(prefs.previewDevice, g.ctx->deviceType(),
                                             convolution ? gpu::PreviewWork::ConvolutionMorph : gpu::PreviewWork::Other);
  if (rt.get() != prewarmedMorph_ && r.morphBackend.gpu) {
    // Compile the GPU pipelines of the morph stage now, in the background, not in the frame
    // that first reaches B (on lavapipe ~1 s per kind of shape: the cross-fade's stand-ins
    // alone and the morph between them).
    prewarmedMorph_ = rt.get();
    gpu::ImplicitPreviewSettings ps;
    ps.interactiveResolution = prefs.previewCoarseResolution;
    ps.gpu = true;
    for (double u : {0.0, 0.5, 1.0}) g.morphPreview->prewarm(*morphPreviewSource(rt, timeSec, u), ps);
  }
  MorphSceneInfo info = applyMorph(frame_, rt, timeSec, morphSettings_, /*implicitStage=*/false);
  ectx.viewportNote = "morph: " + describeMorphStage(info);
  shown.opacity = float(info.implicitOpacity);
  if (shown.opacity > 0.0f) {  // B..C, the cross-fade's window around B and C, the transitions' stand-in core
    gpu::ImplicitPreviewSettings ps;
    ps.threads = previewThreads;
    ps.interactiveResolution = prefs.previewCoarseResolution;
    ps.refinedResolution = prefs.previewResolution;
    ps.gpu = r.morphBackend.gpu;
    ps.settle = settle;
    const double u = info.stage == MorphStage::Morph ? -1.0 : info.implicitProgress;
    g.morphPreview->update(info.implicitCore ? standinCorePreviewSource(rt, timeSec, info.stage == MorphStage::Expand, u)
                                             : morphPreviewSource(rt, timeSec, u),
                           timeSec, ps);
    r.morphStageShown = true;
    shown.sourceId = rt->setup.sourceActorId;
  }
  return shown;
}

// The BlobTree previews updated for frame_; returns the particle systems drawn as particles this
// frame (moving, or their surface not ready yet).
std::vector<ParticleDraw> ViewportFrame::updateBlobPreviews(EditorGpu& g, EditorUI& ui, EditorContext& ectx,
                                                            bool settle, int previewThreads, ViewportFrameResult& r) {
  const Preferences& prefs = ui.state().prefs;
  const Project& project = ectx.document->project();
  // Particle systems moving (scrubbing, playing) are drawn as particles, not polygonised (not for
  // screenshots); so are those spread too far for the surface's grid (editor/particle_view.h).
  ParticleViewSettings pv;
  pv.enabled = prefs.particleView;
  pv.settle = settle;
  pv.surfaceResolution = prefs.previewResolution;
  pv.holding = ui.state().timeline.scrubbing || ui.state().playback.playing();
  std::vector<ParticleDraw> particles = particleView_.takeMoving(frame_, project, ectx.nowSec, pv);
  if (!particleView_.note().empty())
    ectx.viewportNote += (ectx.viewportNote.empty() ? "" : "  |  ") + particleView_.note();
  g.blobPreviews->update(project, frame_,
                         {prefs.previewCoarseResolution, prefs.previewResolution, previewThreads,
                          r.backend.gpu, settle});
  for (ParticleDraw& p : particleView_.takeUnready(frame_, project, [&](const std::string& id) {
         const gpu::ImplicitPreviewStatus st = g.blobPreviews->status(id);
         return !st.refining && (st.hasMesh || !st.error.empty());
       }))
    particles.push_back(std::move(p));
  r.particlesShown = particleView_.pending();
  return particles;
}

// A click in the viewport: the nearest surface (meshes, BlobTree previews, the morph's surface) or
// skeleton marker under it becomes the selection (editor/click_selection.h).
void ViewportFrame::applyClick(EditorGpu& g, EditorContext& ectx, const EditorOutput& out, double timeSec,
                               bool morphStageShown) {
  Document& doc = *ectx.document;
  const glm::vec2 local = out.pick->windowPos - out.viewport.min;
  const Ray ray = out.camera.rayThroughPixel(local.x, local.y, out.viewport.size);
  std::optional<ScenePick> hit = pickScene(frame_, ray);
  for (const BlobDraw& b : frame_.blobs)
    if (auto res = b.opacity < 1.0f ? nullptr : g.blobPreviews->result(b.actorId))  // ghosts are not picked
      hit = nearerPick(hit, pickBlobSurface(b.actorId, b.model, res->mesh, ray));
  if (ectx.morphRuntime && !out.weightPaintMode) {
    auto cpu = morphStageShown ? g.morphPreview->cpuResult() : nullptr;
    hit = nearerPick(hit, pickMorphSurface(*ectx.morphRuntime, timeSec, ray, cpu ? &cpu->mesh : nullptr));
  }
  // With the skeleton hidden, its markers are not there to click.
  auto guide = doc.project().view.showSkeleton ? pickBlobGuide(frame_, out.camera, out.viewport.size, local)
                                               : std::nullopt;
  doc.selection = selectionAfterClick(doc.selection, guide, hit, out.pick->extend);
}

// frame_ made into the renderer's scene with its highlights, particles, the morph's implicit
// stage, stand-in and weight overlays; and the status bar's preview line.
void ViewportFrame::composeScene(EditorGpu& g, EditorUI& ui, EditorContext& ectx, double timeSec,
                                 const std::vector<ParticleDraw>& particles, const MorphShown& morph,
                                 const ViewportFrameResult& r, gpu::Scene& scene) {
  const EditorOutput& out = ui.output();
  Document& doc = *ectx.document;
  const Actor* selActor = doc.project().findActor(doc.selection.actorId);
  const int selBlobNode = selActor && selActor->kind == ActorKind::BlobTree ? doc.selection.node : -1;
  gpu::buildScene(frame_, doc.project().view, doc.selection.actorId, *g.meshes, scene, g.blobPreviews.get(),
                  selBlobNode, g.standinBindings.get());
  if (const Actor* ha = doc.project().findActor(out.highlightBlobNode.actorId);
      ha && ha->kind == ActorKind::BlobTree) {  // a node hovered in the correspondence editor
    AnimationEndScope ends(doc.project(), &doc, doc.revision());
    if (ha->blobTree.find(out.highlightBlobNode.node))
      gpu::addBlobHighlight(blobSubtreeGuides(ha->blobTree, out.highlightBlobNode.node, blobActorTimeSec(*ha, timeSec),
                                              ha->transform.matrix()),
                            scene);
  }
  if (!out.highlightChain.lines.empty()) gpu::addBlobHighlight(out.highlightChain, scene);  // Chain matching's hovered row
  // Particles as spheres in the colour of the BlobTree surfaces they stand for.
  for (const ParticleDraw& p : particles)
    scene.particles.push_back(gpu::particleSpheres(p, gpu::kBlobSurfaceColor, p.actorId == doc.selection.actorId));
  if (r.morphStageShown) {
    const size_t meshCount = scene.meshes.size(), generatedCount = scene.generatedMeshes.size();
    g.morphPreview->draw(scene, glm::mat4(1.0f), {0.62f, 0.62f, 0.62f, 1.0f}, doc.selection.actorId == morph.sourceId);
    gpu::setCrossFade(scene, meshCount, generatedCount, morph.opacity);
  }
  if (doc.project().view.showStandins || ui.state().viewportMode == ViewportMode::StandinEdit)
    gpu::addStandinOverlay(projectStandinGuides(doc.project(), doc.baseDir(), ectx.assets, timeSec, doc.selection.actorId),
                           doc.selection.actorId, selectedStandinSegment(doc), scene.overlay);
  if (!out.weightOverlay.actorId.empty()) {
    overlayWeights_ = out.weightOverlay.weights;
    gpu::addWeightOverlay(frame_, out.weightOverlay.actorId, overlayWeights_, *g.meshes, scene);
  }
  // Status bar: the morph stage's preview, else the selected BlobTree actor's (else the first one's).
  const std::string id = selBlobNode >= 0 || (selActor && selActor->kind == ActorKind::BlobTree)
                             ? doc.selection.actorId
                             : (frame_.blobs.empty() ? std::string() : frame_.blobs.front().actorId);
  if (r.morphStageShown) ectx.stats.previewInfo = gpu::describePreviewStatus(g.morphPreview->status(), r.morphBackend);
  else if (!id.empty()) ectx.stats.previewInfo = gpu::describePreviewStatus(g.blobPreviews->status(id), r.backend);
  else ectx.stats.previewInfo.clear();
}

}  // namespace animorph
