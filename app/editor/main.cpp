// animorph: the editor. The composition root: the window (editor_window), the Vulkan side
// (editor_gpu), the editor UI over the document, the viewport's frame (viewport_frame), the test
// and bench switches (editor_automation), joined in one frame loop that draws on demand.
//
//   animorph [PROJECT | CHARACTER] [--screenshot FILE.png --frame N --quit] [--size WxH] [--bench FRAMES]
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "app/editor/editor_args.h"
#include "app/editor/editor_automation.h"
#include "app/editor/editor_gpu.h"
#include "ui/shell/editor_ui.h"
#include "app/editor/editor_window.h"
#include "app/editor/frame_clock.h"
#include "core/poly/preview_polygonizer.h"
#include "gpu/frame/playblast.h"
#include "core/scene/scrub_pacing.h"
#include "ui/shell/redraw_policy.h"
#include "app/editor/ui_map.h"
#include "app/editor/viewport_frame.h"
#include "gpu/vulkan/vk_check.h"
#include "app/editor/window_events.h"

using namespace animorph;

int main(int argc, char** argv) {
  FrameClock clock;
  EditorArgs args;
  if (!parseEditorArgs(argc, argv, args)) return 2;
  GLFWwindow* window = openEditorWindow(args.width, args.height);
  if (!window) return 1;
  const gpu::SwapchainSettings ss = editorSwapchainSettings(args.benchFrames > 0);
  auto gpuR = createEditorGpu(window, ss);
  if (!gpuR) {
    std::fprintf(stderr, "animorph: %s\n", gpuR.error().c_str());
    closeEditorWindow(window);
    return 1;
  }
  std::unique_ptr<EditorGpu> gpuSide = std::move(*gpuR);

  EditorUI ui;
  const char* demoDir = std::getenv("ANIMORPH_DEMO_DIR");  // Help > Demos: the repository's by default
  ui.setDemoDir(demoDir ? demoDir : ANIMORPH_SOURCE_DIR "/resources/demo");
  AssetCache assets;
  std::unique_ptr<Document> document = std::make_unique<Document>();
  if (!args.project.empty()) ui.requestOpen(args.project);
  EditorContext ectx(document, assets);
  ectx.playblast = gpu::playblastProject;  // File > Export > Playblast...: its own offscreen device
  const char* uiMapPath = std::getenv("ANIMORPH_UI_MAP");
  const char* redrawEnv = std::getenv("ANIMORPH_REDRAW");
  const bool continuousRedraw = redrawEnv && std::strcmp(redrawEnv, "continuous") == 0;
  EditorAutomation automation(args);
  ViewportFrame viewport(ui.state().prefs.previewDevice);
  RedrawPolicy redraw;  // on demand: an idle editor waits for events
  ScrubPacer pacer;     // while scrubbing a CPU preview: a frame per new mesh, input at most once an interval
  gpu::Scene scene;
  std::string lastTitle, pendingCapture;
  int frameCount = 0, captureFrames = 0;  // captureFrames: since pendingCapture was set (taken on the second)
  int exitCode = 0;
  uint64_t eventsSeen = 0;
  clock.startFrames();

  for (;;) {
    glfwPollEvents();
    if (gpu::deviceLost()) {
      auto recovered = recoverLostDevice(window, ss, *document, ectx.nowSec, gpuSide);
      if (!recovered) {
        exitCode = 1;
        break;
      }
      viewport.forgetPrewarm();
      ui.state().status = {*recovered, true};
    }
    const uint64_t events = windowEventCount();
    const bool inputThisFrame = events != eventsSeen;
    eventsSeen = events;
    if (auto dropped = takeDroppedPaths(); !dropped.empty()) ui.requestDrop(std::move(dropped));
    if (glfwWindowShouldClose(window)) {
      glfwSetWindowShouldClose(window, GLFW_FALSE);
      ui.requestQuit();
    }
    clock.tick();
    ectx.nowSec = clock.nowSec();
    ectx.dtSec = clock.dtSec();
    ectx.stats.frameMs = static_cast<float>(clock.smoothedMs());
    ectx.stats.fps = static_cast<float>(clock.smoothedMs() > 0.0 ? 1000.0 / clock.smoothedMs() : 0.0);
    ectx.stats.deviceName = gpuSide->ctx->deviceName();
    automation.beforeUi(*document, ui.state().playback, ectx.nowSec, frameCount,
                        ui.output().jobRunning || viewport.morphPreparing());

    gpuSide->imgui->newFrame();
    const std::string previewInfoDrawn = ectx.stats.previewInfo;  // the status bar below shows this one
    viewport.updateMorphRuntime(ectx, ui.output());  // the inspector shows this frame's morph
    ui.draw(ectx);
    ImGui::Render();
    const EditorOutput& out = ui.output();
    if (out.quit) break;
    if (out.screenshotPath) pendingCapture = *out.screenshotPath;
    if (auto due = automation.screenshotDue(frameCount, out.jobRunning || viewport.morphPreparing())) pendingCapture = *due;
    pacer.frameStarted(ectx.nowSec, events, PreviewPolygonizer::publishedTotal());  // meshes after this are new
    const ViewportFrameResult vf = viewport.build(*gpuSide, ui, ectx, !pendingCapture.empty(), scene);
    // The first frame settles the previews; the second, whose status bar already shows them, is captured.
    if (!pendingCapture.empty() && captureFrames++ >= 1) gpuSide->swapchain->requestCapture();
    const PresentedFrame shown = presentFrame(*gpuSide, out.viewport, out.camera, scene, pendingCapture);
    if (shown.status == gpu::FrameStatus::Ready) automation.firstFrameShown(clock.sinceStartMs());
    if (shown.captured) {
      pendingCapture.clear();
      captureFrames = 0;
      if (automation.quitAfterScreenshot()) break;
    }
    if (shown.status == gpu::FrameStatus::Failed) glfwWaitEventsTimeout(0.1);
    gpuSide->meshes->endFrame();
    gpuSide->blobPreviews->endFrame();
    gpuSide->standinBindings->endFrame();
    gpuSide->morphPreview->endFrame();
    ++frameCount;
    const bool blobBusy = gpuSide->blobPreviews->busy(), morphBusy = gpuSide->morphPreview->busy();
    if (automation.frameDone(frameCount, clock.dtSec(), ectx.nowSec, !blobBusy && !morphBusy, continuousRedraw)) break;

    // Draw the next frame at once, or wait for input (on demand, as Blender does). A skipped
    // frame (swapchain out of date) is drawn again at once; a minimised window waits.
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(window, &fbw, &fbh);
    RedrawState rs;
    rs.input = inputThisFrame;
    const bool movesOnItsOwn = ui.state().playback.playing() || gpuSide->blobPreviews->needsFrames() ||
                               (vf.morphStageShown && gpuSide->morphPreview->needsFrames()) || vf.particlesShown ||
                               frameCount < 10 || automation.needsFrames() || !pendingCapture.empty() ||
                               (shown.status == gpu::FrameStatus::Skipped && fbw > 0 && fbh > 0) || continuousRedraw;
    rs.awaitingWork = blobBusy || (vf.morphStageShown && morphBusy);
    // Scrubbing while the CPU worker computes: paced (scene/scrub_pacing.h), not a frame per motion.
    const bool paced = ScrubPacer::applies(ui.state().timeline.scrubbing, rs.awaitingWork, movesOnItsOwn);
    viewport.setScrubPaced(paced);
    // The status bar is built before the previews update: one more frame shows what they did (a mesh
    // that arrived without input would otherwise sit under a stale "refining" until the idle tick).
    // Paced, the next frame comes with the next mesh or input anyway.
    rs.animating = movesOnItsOwn || (!paced && (ImGui::IsAnyMouseDown() || ectx.stats.previewInfo != previewInfoDrawn));
    rs.jobRunning = out.jobRunning || viewport.morphPreparing();  // polled ten times a second
    rs.textInput = ImGui::GetIO().WantTextInput;
    double waitSec = redraw.waitAfterFrame(rs);
    pacer.setIntervalSec(ScrubPacer::intervalFor(document->project().timeline.fps));
    if (paced)
      waitSec = pacer.waitSec(clock.sinceStartMs() / 1000.0, windowEventCount(), PreviewPolygonizer::publishedTotal());
    if (uiMapPath && (frameCount % 3 == 0 || waitSec > 0.0))
      writeEditorUiMap(uiMapPath, ui, ectx, frameCount,
                       {rs.awaitingWork, waitSec > 0.0, clock.tickEpochSec(),
                        vf.morphStageShown ? vf.morphBackend.gpu : vf.backend.gpu, gpuSide->swapchain->presentPath(),
                        vf.particlesShown, paced});
    const std::string title = "Animorph - " + document->displayName() + (document->dirty() ? " *" : "");
    if (title != lastTitle) glfwSetWindowTitle(window, (lastTitle = title).c_str());
    if (waitSec > 0.0) {
      Status flushed = gpuSide->swapchain->flushPresentation();  // the last frame is in the window before we wait
      if (!flushed) std::fprintf(stderr, "animorph: %s\n", flushed.error().c_str());
      glfwWaitEventsTimeout(waitSec);
      // Paced: events before the interval is up (the cursor moving) are taken in by the next frame.
      while (paced && (waitSec = pacer.waitSec(clock.sinceStartMs() / 1000.0, windowEventCount(),
                                               PreviewPolygonizer::publishedTotal())) > 0.0)
        glfwWaitEventsTimeout(waitSec);
      if (!paced) clock.woke();  // frame times and playback count from the wake, not the wait
    }
  }

  if (gpuSide) {  // else: the device was lost and could not be remade (said above)
    automation.printBench(gpuSide->ctx->deviceName(), gpuSide->swapchain->presentPath());
    gpuSide->ctx->waitIdle();
    if (gpuSide->ctx->validationEnabled() && gpuSide->ctx->validationErrorCount() > 0) {
      std::fprintf(stderr, "animorph: %u Vulkan validation error(s)\n", gpuSide->ctx->validationErrorCount());
      exitCode = 3;
    }
  }
  ui.savePreferences();
  gpuSide.reset();
  closeEditorWindow(window);
  return exitCode;
}
