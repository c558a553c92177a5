// animorph: the editor. Wiring only: window, Vulkan, ImGui, the editor UI,
// scene evaluation and the renderer, joined in one frame loop.
//
//   animorph [PROJECT] [--screenshot FILE.png --frame N --quit] [--size WxH] [--bench FRAMES]
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "editor_gpu.h"
#include "editor_args.h"
#include "editor_ui.h"
#include "implicit_preview.h"
#include "imgui_vulkan.h"
#include "mesh_cache.h"
#include "redraw_policy.h"
#include "scene/animorphosis_scene.h"
#include "scene/morph_preview_source.h"
#include "scene/morph_pick.h"
#include "scene/morph_scene.h"
#include "scene/blob_pick.h"
#include "scene/pick.h"
#include "scene/standin_guides.h"
#include "scene/scene_frame.h"
#include "scene_from_frame.h"
#include "scene_renderer.h"
#include "standin_binding_cache.h"
#include "standin_overlay.h"
#include "swapchain.h"
#include "vk_check.h"
#include "paint/paint_mesh.h"
#include "weight_overlay_scene.h"
#include "ui_map.h"
#include "window_events.h"

using namespace animorph;
using Clock = std::chrono::steady_clock;

namespace {

double processCpuSec() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  const auto startTime = Clock::now();
  EditorArgs args;
  if (!parseEditorArgs(argc, argv, args)) return 2;

  if (!glfwInit()) {
    std::fprintf(stderr, "animorph: cannot open a window (no display?). Run under a virtual X server:\n"
                         "  xvfb-run -a animorph ...   or use animorph-cli for headless work.\n");
    return 1;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window = glfwCreateWindow(args.width, args.height, "Animorph", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "animorph: could not create a window\n");
    glfwTerminate();
    return 1;
  }

  watchWindowEvents(window);  // before ImGui's backend, which chains to these callbacks
  PreviewPolygonizer::setPublishHook([] { glfwPostEmptyEvent(); });  // a preview mesh wakes the frame loop

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout lives in our preferences
  EditorUI::applyStyle();                // before the swapchain: the window is cleared to the panels' colour
  gpu::SwapchainSettings ss;
  {
    float c[4];
    EditorUI::windowClearColor(c);
    ss.clearColor = glm::vec4(c[0], c[1], c[2], c[3]);
  }
  if (args.benchFrames > 0) ss.presentMode = gpu::PresentMode::Immediate;
  auto gpuR = createEditorGpu(window, ss);
  if (!gpuR) {
    std::fprintf(stderr, "animorph: %s\n", gpuR.error().c_str());
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return 1;
  }
  std::unique_ptr<EditorGpu> gpuSide = std::move(*gpuR);

  EditorUI ui;
  AssetCache assets;
  PreviewDevice previewDevice = ui.state().prefs.previewDevice;
  std::unique_ptr<Document> document = std::make_unique<Document>();
  if (!args.project.empty()) ui.requestOpen(args.project);
  EditorContext ectx(document, assets);
  ectx.stats.deviceName = gpuSide->ctx->deviceName();

  const char* uiMapEnv = std::getenv("ANIMORPH_UI_MAP");
  const std::string uiMapPath = uiMapEnv ? uiMapEnv : "";
  gpu::Scene scene;
  MorphCache morphCache;
  AnimorphosisCache animorphosisCache;  // the generic tree C of the project's animorphosis
  MorphFrameSettings morphSettings;  // the transitions; the B->C stage is morphPreview's
  const MorphRuntime* prewarmedMorph = nullptr;  // whose B->C pipelines are compiling or compiled
  std::vector<float> overlayWeights;  // the weight overlay's data, alive until the frame is recorded
  // Collapse and expansion run in the vertex shader (ANIMORPH_CPU_TRANSITIONS=1: on the CPU, for comparison).
  morphSettings.gpuTransitions = !std::getenv("ANIMORPH_CPU_TRANSITIONS");
  std::string lastTitle;
  std::vector<double> frameMs;
  double firstFrameMs = -1.0;
  int frameCount = 0, screenshotAt = -1;
  bool frameApplied = false;
  std::string pendingCapture;
  int captureFrames = 0;  // frames since pendingCapture was set: the capture is taken on the second
  int exitCode = 0;
  auto prev = Clock::now();
  double smoothedMs = 16.0;
  RedrawPolicy redraw;  // on demand: an idle editor waits for events
  uint64_t eventsSeen = 0;
  bool wokeFromWait = false;
  const char* redrawEnv = std::getenv("ANIMORPH_REDRAW");
  const bool continuousRedraw = redrawEnv && std::strcmp(redrawEnv, "continuous") == 0;
  // --idle-bench: from 2 s after start-up (the project open, the preview refined), S seconds without input.
  double idleStartSec = -1.0, idleStartCpu = 0.0;
  int idleStartFrames = 0;

  for (;;) {
    glfwPollEvents();
    if (gpu::deviceLost()) {
      // The device is gone with everything made on it (a driver reset, a GPU removed): save the
      // work, then remake the Vulkan side; the document, the UI and its state stay as they are.
      const bool autosaved = document->autosaveIfDue(ectx.nowSec, 0.0);
      std::fprintf(stderr, "animorph: the GPU device was lost; recreating the renderer%s\n",
                   autosaved ? (" (work autosaved to " + document->autosavePath() + ")").c_str() : "");
      gpuSide.reset();
      gpu::clearDeviceLost();
      auto again = createEditorGpu(window, ss);
      if (!again) {
        std::fprintf(stderr, "animorph: cannot recreate the renderer: %s; quitting%s\n", again.error().c_str(),
                     document->dirty() ? " (the autosave is offered when the project is opened again)" : "");
        exitCode = 1;
        break;
      }
      gpuSide = std::move(*again);
      prewarmedMorph = nullptr;
      ectx.stats.deviceName = gpuSide->ctx->deviceName();
      ui.state().status = {std::string("The GPU device was lost; the renderer was recreated") +
                               (autosaved ? " (work autosaved)" : ""),
                           true};
    }
    gpu::Context& ctx = *gpuSide->ctx;
    gpu::Swapchain& swapchain = *gpuSide->swapchain;
    gpu::SceneRenderer& renderer = *gpuSide->renderer;
    ImGuiVulkan& imgui = *gpuSide->imgui;
    gpu::MeshCache& meshes = *gpuSide->meshes;
    gpu::BlobPreviewSet* blobPreviews = gpuSide->blobPreviews.get();
    gpu::StandinBindingCache* standinBindings = gpuSide->standinBindings.get();
    gpu::ImplicitPreview* morphPreview = gpuSide->morphPreview.get();
    const uint64_t events = windowEventCount();
    const bool inputThisFrame = events != eventsSeen;
    eventsSeen = events;
    if (auto dropped = takeDroppedPaths(); !dropped.empty()) ui.requestDrop(std::move(dropped));
    if (glfwWindowShouldClose(window)) {
      glfwSetWindowShouldClose(window, GLFW_FALSE);
      ui.requestQuit();
    }
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - prev).count();
    prev = now;
    // After a wait for events the previous frame's rendering finished during the wait: its
    // time says nothing of the frame rate, which the status bar shows as of the last run of frames.
    if (!wokeFromWait) smoothedMs = 0.9 * smoothedMs + 0.1 * dt * 1000.0;
    wokeFromWait = false;
    ectx.nowSec = std::chrono::duration<double>(now - startTime).count();
    ectx.dtSec = dt;
    ectx.stats.frameMs = static_cast<float>(smoothedMs);
    ectx.stats.fps = static_cast<float>(smoothedMs > 0.0 ? 1000.0 / smoothedMs : 0.0);

    // The command-line frame is applied once the project is open.
    if (args.frame >= 0 && !frameApplied && frameCount >= 2) {
      document->setCurrentFrame(args.frame);
      frameApplied = true;
    }
    if (args.benchFrames > 0 && args.scrubFrom >= 0 && frameCount >= 2) {
      // A..B..A, one step per redraw: the preview sees a new time every frame, as when dragging.
      static const double scrubStart = ectx.nowSec;
      const long step = args.scrubHz > 0.0 ? long((ectx.nowSec - scrubStart) * args.scrubHz) : long(frameCount - 2);
      const int span = args.scrubTo - args.scrubFrom, k = int(step % (2 * span));
      document->setCurrentFrame(args.scrubFrom + (k <= span ? k : 2 * span - k));
    } else if (args.benchFrames > 0 && frameCount == 2 && !ui.state().playback.playing())
      ui.state().playback.toggle(document->project().timeline);

    imgui.newFrame();
    const std::string previewInfoDrawn = ectx.stats.previewInfo;  // the status bar below shows this one
    ui.draw(ectx);
    ImGui::Render();
    const EditorOutput& out = ui.output();
    if (out.quit) break;

    Document& doc = *document;
    const Timeline& tl = doc.project().timeline;
    const double timeSec = tl.frameToSec(tl.currentFrame);
    SceneFrame frame = evaluateScene(doc.project(), doc.baseDir(), assets, timeSec);
    if (out.screenshotPath) pendingCapture = *out.screenshotPath;
    if (!args.screenshot.empty() && screenshotAt < 0 && frameApplied == (args.frame >= 0) && frameCount >= 6) {
      pendingCapture = args.screenshot;
      screenshotAt = frameCount;
    }
    const Preferences& prefs = ui.state().prefs;
    const gpu::PreviewBackend backend = gpu::choosePreviewBackend(prefs.previewDevice, ctx.deviceType());
    if (prefs.previewDevice != previewDevice) {  // the user switched: try the GPU again
      previewDevice = prefs.previewDevice;
      morphPreview->clearGpuFailure();
      blobPreviews->clearGpuFailures();
    }
    // Not while painting: every stroke is a new revision and would bind the vertices again.
    if (!out.weightPaintMode) ectx.morphRuntime = morphCache.get(doc.project(), doc.baseDir(), assets, &doc, doc.revision());
    gpu::PreviewBackend morphBackend = backend;  // the morph stage's (its stand-ins decide Auto on CPU devices)
    bool morphStageShown = false;
    float morphOpacity = 0.0f;  // below 1: the cross-fade (dithered, complementary to the mesh)
    std::string morphSourceId;
    if (out.weightPaintMode) {  // the painted actor as itself, posed, without the morph
      isolateForPainting(frame, doc.project().morph, out.weightOverlay.actorId);
      ectx.viewportNote.clear();
    } else if (auto rt = ectx.morphRuntime) {
      const bool convolution = rt->source.morph.standin.kind == StandinKind::Convolution &&
                               rt->target.morph.standin.kind == StandinKind::Convolution;
      morphBackend = gpu::choosePreviewBackend(prefs.previewDevice, ctx.deviceType(),
                                               convolution ? gpu::PreviewWork::ConvolutionMorph : gpu::PreviewWork::Other);
      if (rt.get() != prewarmedMorph && morphBackend.gpu) {
        // Compile the GPU pipelines of the morph stage now, in the background, not in the frame
        // that first reaches B (on lavapipe ~1 s per kind of shape: the cross-fade's stand-ins
        // alone and the morph between them).
        prewarmedMorph = rt.get();
        gpu::ImplicitPreviewSettings ps;
        ps.interactiveResolution = prefs.previewCoarseResolution;
        ps.gpu = true;
        for (double u : {0.0, 0.5, 1.0}) morphPreview->prewarm(*morphPreviewSource(rt, timeSec, u), ps);
      }
      MorphSceneInfo info = applyMorph(frame, rt, timeSec, morphSettings, /*implicitStage=*/false);
      ectx.viewportNote = "morph: " + describeMorphStage(info);
      morphOpacity = float(info.implicitOpacity);
      if (morphOpacity > 0.0f) {  // B..C, or the cross-fade's window around B and C
        gpu::ImplicitPreviewSettings ps;
        ps.threads = interactivePreviewThreads();
        ps.interactiveResolution = prefs.previewCoarseResolution;
        ps.refinedResolution = prefs.previewResolution;
        ps.gpu = morphBackend.gpu;
        ps.settle = !pendingCapture.empty();
        const double u = info.stage == MorphStage::Morph ? -1.0 : info.implicitProgress;
        morphPreview->update(morphPreviewSource(rt, timeSec, u), timeSec, ps);
        morphStageShown = true;
        morphSourceId = rt->setup.sourceActorId;
      }
    } else {
      ectx.viewportNote = morphCache.error().empty() ? "" : "morph: " + morphCache.error();
    }
    if (!out.weightPaintMode) {
      const std::string note =
          describeAnimorphosis(applyAnimorphosis(frame, doc.project(), animorphosisCache, &doc, doc.revision()));
      if (!note.empty()) ectx.viewportNote += (ectx.viewportNote.empty() ? "" : "  |  ") + note;
    }
    blobPreviews->update(doc.project(), frame,
                         {prefs.previewCoarseResolution, prefs.previewResolution, interactivePreviewThreads(), backend.gpu,
                          /*settle=*/!pendingCapture.empty()});
    if (out.pick) {
      glm::vec2 local = out.pick->windowPos - out.viewport.min;
      Ray ray = out.camera.rayThroughPixel(local.x, local.y, out.viewport.size);
      auto hit = pickScene(frame, ray);
      for (const BlobDraw& b : frame.blobs) {
        auto r = blobPreviews->result(b.actorId);
        if (!r) continue;
        auto bh = pickBlobSurface(b.actorId, b.model, r->mesh, ray);
        if (bh && (!hit || bh->distance < hit->distance)) hit = bh;
      }
      if (ectx.morphRuntime && !out.weightPaintMode) {
        auto cpu = morphStageShown ? morphPreview->cpuResult() : nullptr;
        auto mh = pickMorphSurface(*ectx.morphRuntime, timeSec, ray, cpu ? &cpu->mesh : nullptr);
        if (mh && (!hit || mh->distance < hit->distance)) hit = mh;
      }
      // A skeleton marker under the cursor selects its node; with the skeleton
      // hidden, markers are not there to click.
      auto guide = doc.project().view.showSkeleton ? pickBlobGuide(frame, out.camera, out.viewport.size, local)
                                                   : std::nullopt;
      if (guide) doc.selection = Selection{guide->actorId, guide->node};
      else if (hit) doc.selection = Selection{hit->actorId, -1};
      else if (!out.pick->extend) doc.selection = {};
    }

    // A screenshot shows the refined implicit surfaces, not whatever is ready.
    if (!pendingCapture.empty() && !blobPreviews->waitIdle(120.0))
      std::fprintf(stderr, "animorph: BlobTree preview still computing at the screenshot\n");
    if (!pendingCapture.empty() && morphStageShown && !morphPreview->waitIdle(120.0))
      std::fprintf(stderr, "animorph: morph preview still computing at the screenshot\n");
    const Actor* selActor = doc.project().findActor(doc.selection.actorId);
    int selBlobNode = selActor && selActor->kind == ActorKind::BlobTree ? doc.selection.node : -1;
    gpu::buildScene(frame, doc.project().view, doc.selection.actorId, meshes, scene, blobPreviews, selBlobNode,
                    standinBindings);
    if (const Actor* ha = doc.project().findActor(out.highlightBlobNode.actorId);
        ha && ha->kind == ActorKind::BlobTree) {  // a node hovered in the correspondence editor
      if (const BlobNode* hn = ha->blobTree.find(out.highlightBlobNode.node))
        gpu::addBlobHighlight(
            subtreeGuides(blobGuides(ha->blobTree, blobActorTimeSec(*ha, timeSec), ha->transform.matrix()), *hn), scene);
    }
    if (morphStageShown) {
      const size_t meshCount = scene.meshes.size(), generatedCount = scene.generatedMeshes.size();
      morphPreview->draw(scene, glm::mat4(1.0f), {0.62f, 0.62f, 0.62f, 1.0f}, doc.selection.actorId == morphSourceId);
      gpu::setCrossFade(scene, meshCount, generatedCount, morphOpacity);
    }
    if (doc.project().view.showStandins || ui.state().viewportMode == ViewportMode::StandinEdit)
      gpu::addStandinOverlay(projectStandinGuides(doc.project(), doc.baseDir(), assets, timeSec, doc.selection.actorId),
                             doc.selection.actorId, selectedStandinSegment(doc, ui.state().standinTool), scene.overlay);
    if (!out.weightOverlay.actorId.empty()) {
      overlayWeights = out.weightOverlay.weights;
      gpu::addWeightOverlay(frame, out.weightOverlay.actorId, overlayWeights, meshes, scene);
    }
    {
      // Status bar: the morph stage's preview, else the selected BlobTree actor's (else the first one's).
      std::string id = selBlobNode >= 0 || (selActor && selActor->kind == ActorKind::BlobTree)
                           ? doc.selection.actorId
                           : (frame.blobs.empty() ? std::string() : frame.blobs.front().actorId);
      if (morphStageShown) ectx.stats.previewInfo = gpu::describePreviewStatus(morphPreview->status(), morphBackend);
      else if (!id.empty()) ectx.stats.previewInfo = gpu::describePreviewStatus(blobPreviews->status(id), backend);
      else ectx.stats.previewInfo.clear();
    }
    // The first frame settles the previews; the second, whose status bar already shows them, is captured.
    if (!pendingCapture.empty() && captureFrames++ >= 1) swapchain.requestCapture();

    gpu::Frame f;
    gpu::FrameStatus fs = swapchain.beginFrame(f);
    if (fs == gpu::FrameStatus::Ready) {
      ImGuiIO& io = ImGui::GetIO();
      const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
      gpu::ViewportRect rect;
      rect.x = static_cast<int32_t>(out.viewport.min.x * sx);
      rect.y = static_cast<int32_t>(out.viewport.min.y * sy);
      rect.width = static_cast<uint32_t>(std::max(0.0f, out.viewport.size.x * sx));
      rect.height = static_cast<uint32_t>(std::max(0.0f, out.viewport.size.y * sy));
      rect.width = std::min(rect.width, f.extent.width - std::min<uint32_t>(f.extent.width, rect.x));
      rect.height = std::min(rect.height, f.extent.height - std::min<uint32_t>(f.extent.height, rect.y));
      if (rect.width > 0 && rect.height > 0) {
        Status st = renderer.record(f.cmd, f.serial, rect, out.camera, scene);
        if (!st) std::fprintf(stderr, "animorph: %s\n", st.error().c_str());
      }
      Status ui = imgui.record(f.cmd, f.slot);
      if (!ui) std::fprintf(stderr, "animorph: %s\n", ui.error().c_str());
      Status st = swapchain.endFrame();
      if (!st) std::fprintf(stderr, "animorph: %s\n", st.error().c_str());
      if (firstFrameMs < 0.0) {
        firstFrameMs = std::chrono::duration<double, std::milli>(Clock::now() - startTime).count();
      }
      if (auto img = swapchain.takeCapture(); img && !pendingCapture.empty()) {
        Status w = gpu::writePng(pendingCapture, *img);
        if (!w) std::fprintf(stderr, "animorph: %s\n", w.error().c_str());
        pendingCapture.clear();
        captureFrames = 0;
        if (args.quit && screenshotAt >= 0) break;
      }
    } else if (fs == gpu::FrameStatus::Failed) {
      std::fprintf(stderr, "animorph: %s\n", swapchain.lastError().c_str());
      glfwWaitEventsTimeout(0.1);
    }
    meshes.endFrame();
    blobPreviews->endFrame();
    standinBindings->endFrame();
    morphPreview->endFrame();
    ++frameCount;
    if (args.benchFrames > 0 && frameCount > 10) {
      frameMs.push_back(dt * 1000.0);
      if (static_cast<int>(frameMs.size()) >= args.benchFrames) break;
    }
    if (args.screenshot.empty() && args.quit && frameCount > 3) break;
    if (args.idleBenchSec > 0.0) {
      const bool settled = !blobPreviews->busy() && !morphPreview->busy();
      if (idleStartSec < 0.0 && ((ectx.nowSec >= 2.0 && settled) || ectx.nowSec >= 30.0)) {  // (a preview that never settles)
        idleStartSec = ectx.nowSec;
        idleStartCpu = processCpuSec();
        idleStartFrames = frameCount;
      } else if (idleStartSec >= 0.0 && ectx.nowSec - idleStartSec >= args.idleBenchSec) {
        const double sec = ectx.nowSec - idleStartSec;
        std::printf("idle over %.1f s: %d frames, CPU %.1f ms per second (%s redraw)\n", sec,
                    frameCount - idleStartFrames, 1e3 * (processCpuSec() - idleStartCpu) / sec,
                    continuousRedraw ? "continuous" : "on-demand");
        break;
      }
    }

    // Draw the next frame at once, or wait for input (on demand, as Blender does). A skipped
    // frame (swapchain out of date) is drawn again at once; a minimised window waits.
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(window, &fbw, &fbh);
    const bool minimised = fbw == 0 || fbh == 0;
    const bool previewBusy = blobPreviews->busy() || (morphStageShown && morphPreview->busy());
    RedrawState rs;
    rs.input = inputThisFrame;
    const bool previewNeedsFrames = blobPreviews->needsFrames() || (morphStageShown && morphPreview->needsFrames());
    rs.animating = ui.state().playback.playing() || previewNeedsFrames || ImGui::IsAnyMouseDown() || frameCount < 10 ||
                   args.benchFrames > 0 || args.quit || !args.screenshot.empty() || !pendingCapture.empty() ||
                   (args.frame >= 0 && !frameApplied) || (fs == gpu::FrameStatus::Skipped && !minimised);
    // The status bar is built before the previews update: one more frame shows what they did (a mesh
    // that arrived without input would otherwise sit under a stale "refining" until the idle tick).
    rs.animating |= continuousRedraw || ectx.stats.previewInfo != previewInfoDrawn;
    rs.awaitingWork = previewBusy;
    rs.textInput = ImGui::GetIO().WantTextInput;
    const double waitSec = redraw.waitAfterFrame(rs);

    if (!uiMapPath.empty() && (frameCount % 3 == 0 || waitSec > 0.0))
      writeUiMap(uiMapPath, ui.widgets(), out, doc, frameCount,
                 {{"preview_busy", previewBusy},
                  {"idle", waitSec > 0.0},
                  {"status", ui.state().status.text},
                  // CLOCK_MONOTONIC seconds when this frame took its input: a test knows input it sent
                  // before then has been processed once the editor is idle (gui_driver.fresh_map).
                  {"polled_at", std::chrono::duration<double>(now.time_since_epoch()).count()},
                  {"preview", ectx.stats.previewInfo},
                  {"preview_gpu", morphStageShown ? morphBackend.gpu : backend.gpu},
                  {"present", swapchain.presentPath()},
                  {"standin_segment", selectedStandinSegment(doc, ui.state().standinTool)}});
    std::string title = "Animorph - " + doc.displayName() + (doc.dirty() ? " *" : "");
    if (title != lastTitle) {
      glfwSetWindowTitle(window, title.c_str());
      lastTitle = title;
    }
    if (waitSec > 0.0) {
      Status shown = swapchain.flushPresentation();  // the last frame is in the window before we wait
      if (!shown) std::fprintf(stderr, "animorph: %s\n", shown.error().c_str());
      glfwWaitEventsTimeout(waitSec);
      prev = Clock::now();  // frame times and playback count from the wake, not the wait
      wokeFromWait = true;
    }
  }

  if (!gpuSide) {  // the device was lost and could not be remade (said above)
    ui.savePreferences();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return exitCode;
  }
  gpu::Context& ctx = *gpuSide->ctx;
  if (args.benchFrames > 0) {
    std::printf("start to first frame: %.1f ms\n", firstFrameMs);
    std::printf("present: %s\n", gpuSide->swapchain->presentPath().c_str());
    std::printf("frame time over %zu frames: p50 %.2f ms, p95 %.2f ms, max %.2f ms (device: %s)\n", frameMs.size(),
                percentile(frameMs, 0.5), percentile(frameMs, 0.95), percentile(frameMs, 1.0),
                ctx.deviceName().c_str());
  }
  ctx.waitIdle();
  ui.savePreferences();
  if (ctx.validationEnabled() && ctx.validationErrorCount() > 0) {
    std::fprintf(stderr, "animorph: %u Vulkan validation error(s)\n", ctx.validationErrorCount());
    exitCode = 3;
  }
  gpuSide.reset();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return exitCode;
}
