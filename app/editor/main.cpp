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

namespace {

// What the wait after a frame weighs: this frame's input, what its viewport drew and presented, and
// whether the previews still work.
struct FrameOutcome {
  bool input = false;
  ViewportFrameResult viewport;
  PresentedFrame shown;
  bool blobBusy = false, morphBusy = false;
  std::string previewInfoDrawn;  // the status bar's preview line as this frame drew it
};

// The editor's parts, wired once, and the frame loop over them.
class Editor {
 public:
  Editor(const EditorArgs& args, GLFWwindow* window, const gpu::SwapchainSettings& ss,
         std::unique_ptr<EditorGpu> gpuSide, FrameClock& clock);

  // One frame: input, the UI, the viewport, presentation, then the wait for the next one. False when
  // the loop ends (quit, a screenshot taken with --quit, a bench done, a lost device not remade).
  bool frame();
  // After the loop: the bench figures, validation errors (exit status 3), the preferences saved, the
  // Vulkan side and the window closed. Returns the exit status.
  int finish();

 private:
  bool recoverIfDeviceLost();
  void takeWindowRequests();
  void tickClock();
  void endGpuFrame();
  void waitForNextFrame(const FrameOutcome& f);

  GLFWwindow* window_;
  gpu::SwapchainSettings ss_;
  std::unique_ptr<EditorGpu> gpuSide_;
  FrameClock& clock_;
  EditorUI ui_;
  AssetCache assets_;
  std::unique_ptr<Document> document_ = std::make_unique<Document>();
  EditorContext ectx_{document_, assets_};
  EditorAutomation automation_;
  ViewportFrame viewport_{ui_.state().prefs.previewDevice};
  RedrawPolicy redraw_;  // on demand: an idle editor waits for events
  ScrubPacer pacer_;     // while scrubbing a CPU preview: a frame per new mesh, input at most once an interval
  gpu::Scene scene_;
  const char* uiMapPath_ = std::getenv("ANIMORPH_UI_MAP");
  bool continuousRedraw_ = false;
  std::string lastTitle_, pendingCapture_;
  int frameCount_ = 0, captureFrames_ = 0;  // captureFrames_: since pendingCapture_ was set (taken on the second)
  int exitCode_ = 0;
  uint64_t eventsSeen_ = 0;
  // Frames that rendered the 3D scene, and that showed the kept viewport image instead (the bench
  // counts from its first measured frame, like its frame times).
  int scenePasses_ = 0, keptFrames_ = 0, benchScenePasses_ = 0, benchKeptFrames_ = 0;
};

Editor::Editor(const EditorArgs& args, GLFWwindow* window, const gpu::SwapchainSettings& ss,
               std::unique_ptr<EditorGpu> gpuSide, FrameClock& clock)
    : window_(window), ss_(ss), gpuSide_(std::move(gpuSide)), clock_(clock), automation_(args) {
  const char* demoDir = std::getenv("ANIMORPH_DEMO_DIR");  // Help > Demos: the repository's by default
  ui_.setDemoDir(demoDir ? demoDir : ANIMORPH_SOURCE_DIR "/resources/demo");
  if (!args.project.empty()) ui_.requestOpen(args.project);
  ectx_.playblast = gpu::playblastProject;  // File > Export > Playblast...: its own offscreen device
  const char* redrawEnv = std::getenv("ANIMORPH_REDRAW");
  continuousRedraw_ = redrawEnv && std::strcmp(redrawEnv, "continuous") == 0;
}

bool Editor::recoverIfDeviceLost() {
  if (!gpu::deviceLost()) return true;
  auto recovered = recoverLostDevice(window_, ss_, *document_, ectx_.nowSec, gpuSide_);
  if (!recovered) return false;
  viewport_.forgetPrewarm();
  ui_.state().status = {*recovered, true};
  return true;
}

// Files dropped on the window and its close button become the UI's requests.
void Editor::takeWindowRequests() {
  if (auto dropped = takeDroppedPaths(); !dropped.empty()) ui_.requestDrop(std::move(dropped));
  if (glfwWindowShouldClose(window_)) {
    glfwSetWindowShouldClose(window_, GLFW_FALSE);
    ui_.requestQuit();
  }
}

void Editor::tickClock() {
  clock_.tick();
  ectx_.nowSec = clock_.nowSec();
  ectx_.dtSec = clock_.dtSec();
  ectx_.stats.frameMs = static_cast<float>(clock_.smoothedMs());
  ectx_.stats.fps = static_cast<float>(clock_.smoothedMs() > 0.0 ? 1000.0 / clock_.smoothedMs() : 0.0);
  ectx_.stats.deviceName = gpuSide_->ctx->deviceName();
}

void Editor::endGpuFrame() {
  gpuSide_->meshes->endFrame();
  gpuSide_->blobPreviews->endFrame();
  gpuSide_->standinBindings->endFrame();
  gpuSide_->morphPreview->endFrame();
}

bool Editor::frame() {
  glfwPollEvents();
  if (!recoverIfDeviceLost()) {
    exitCode_ = 1;
    return false;
  }
  const uint64_t events = windowEventCount();
  FrameOutcome f;
  f.input = events != eventsSeen_;
  eventsSeen_ = events;
  takeWindowRequests();
  tickClock();
  automation_.beforeUi(*document_, ui_.state().playback, ectx_.nowSec, frameCount_,
                       ui_.output().jobRunning || viewport_.morphPreparing());

  gpuSide_->imgui->newFrame();
  f.previewInfoDrawn = ectx_.stats.previewInfo;  // the status bar below shows this one
  viewport_.updateMorphRuntime(ectx_, ui_.output());  // the inspector shows this frame's morph
  ui_.draw(ectx_);
  ImGui::Render();
  const EditorOutput& out = ui_.output();
  if (out.quit) return false;
  if (out.screenshotPath) pendingCapture_ = *out.screenshotPath;
  if (auto due = automation_.screenshotDue(frameCount_, out.jobRunning || viewport_.morphPreparing()))
    pendingCapture_ = *due;
  pacer_.frameStarted(ectx_.nowSec, events, PreviewPolygonizer::publishedTotal());  // meshes after this are new
  f.viewport = viewport_.build(*gpuSide_, ui_, ectx_, !pendingCapture_.empty(), scene_);
  // The first frame settles the previews; the second, whose status bar already shows them, is captured.
  if (!pendingCapture_.empty() && captureFrames_++ >= 1) gpuSide_->swapchain->requestCapture();
  f.shown = presentFrame(*gpuSide_, out.viewport, out.camera, scene_, pendingCapture_);
  if (f.shown.status == gpu::FrameStatus::Ready) automation_.firstFrameShown(clock_.sinceStartMs());
  if (frameCount_ == 10) benchScenePasses_ = scenePasses_, benchKeptFrames_ = keptFrames_;  // the bench's first frame
  scenePasses_ += f.shown.scenePass;
  keptFrames_ += f.shown.sceneKept;
  automation_.noteFrame(f.shown.scenePass, document_->project().timeline.currentFrame);
  if (f.shown.captured) {
    pendingCapture_.clear();
    captureFrames_ = 0;
    if (automation_.quitAfterScreenshot()) return false;
  }
  if (f.shown.status == gpu::FrameStatus::Failed) glfwWaitEventsTimeout(0.1);
  endGpuFrame();
  ++frameCount_;
  f.blobBusy = gpuSide_->blobPreviews->busy();
  f.morphBusy = gpuSide_->morphPreview->busy();
  if (automation_.frameDone(frameCount_, clock_.dtSec(), ectx_.nowSec, !f.blobBusy && !f.morphBusy, continuousRedraw_))
    return false;
  waitForNextFrame(f);
  return true;
}

// Draw the next frame at once, or wait for input (on demand, as Blender does). A skipped frame
// (swapchain out of date) is drawn again at once; a minimised window waits.
void Editor::waitForNextFrame(const FrameOutcome& f) {
  const ViewportFrameResult& vf = f.viewport;
  int fbw = 0, fbh = 0;
  glfwGetFramebufferSize(window_, &fbw, &fbh);
  RedrawState rs;
  rs.input = f.input;
  const bool movesOnItsOwn = ui_.state().playback.playing() || gpuSide_->blobPreviews->needsFrames() ||
                             (vf.morphStageShown && gpuSide_->morphPreview->needsFrames()) || vf.particlesShown ||
                             frameCount_ < 10 || automation_.needsFrames() || !pendingCapture_.empty() ||
                             (f.shown.status == gpu::FrameStatus::Skipped && fbw > 0 && fbh > 0) || continuousRedraw_;
  rs.awaitingWork = f.blobBusy || (vf.morphStageShown && f.morphBusy);
  // Scrubbing while the CPU worker computes: paced (scene/scrub_pacing.h), not a frame per motion.
  const bool paced = ScrubPacer::applies(ui_.state().timeline.scrubbing, rs.awaitingWork, movesOnItsOwn);
  viewport_.setScrubPaced(paced);
  // The status bar is built before the previews update: one more frame shows what they did (a mesh
  // that arrived without input would otherwise sit under a stale "refining" until the idle tick).
  // Paced, the next frame comes with the next mesh or input anyway.
  rs.animating = movesOnItsOwn || (!paced && (ImGui::IsAnyMouseDown() || ectx_.stats.previewInfo != f.previewInfoDrawn));
  rs.jobRunning = ui_.output().jobRunning || viewport_.morphPreparing();  // polled ten times a second
  rs.textInput = ImGui::GetIO().WantTextInput;
  double waitSec = redraw_.waitAfterFrame(rs);
  pacer_.setIntervalSec(ScrubPacer::intervalFor(document_->project().timeline.fps));
  if (paced)
    waitSec = pacer_.waitSec(clock_.sinceStartMs() / 1000.0, windowEventCount(), PreviewPolygonizer::publishedTotal());
  if (uiMapPath_ && (frameCount_ % 3 == 0 || waitSec > 0.0))
    writeEditorUiMap(uiMapPath_, ui_, ectx_, frameCount_,
                     {rs.awaitingWork, waitSec > 0.0, clock_.tickEpochSec(),
                      vf.morphStageShown ? vf.morphBackend.gpu : vf.backend.gpu, gpuSide_->swapchain->presentPath(),
                      vf.particlesShown, paced, scenePasses_, keptFrames_});
  const std::string title = "Animorph - " + document_->displayName() + (document_->dirty() ? " *" : "");
  if (title != lastTitle_) glfwSetWindowTitle(window_, (lastTitle_ = title).c_str());
  if (waitSec <= 0.0) return;
  Status flushed = gpuSide_->swapchain->flushPresentation();  // the last frame is in the window before we wait
  if (!flushed) std::fprintf(stderr, "animorph: %s\n", flushed.error().c_str());
  glfwWaitEventsTimeout(waitSec);
  // Paced: events before the interval is up (the cursor moving) are taken in by the next frame.
  while (paced && (waitSec = pacer_.waitSec(clock_.sinceStartMs() / 1000.0, windowEventCount(),
                                            PreviewPolygonizer::publishedTotal())) > 0.0)
    glfwWaitEventsTimeout(waitSec);
  if (!paced) clock_.woke();  // frame times and playback count from the wake, not the wait
}

int Editor::finish() {
  if (gpuSide_) {  // else: the device was lost and could not be remade (said above)
    automation_.printBench(gpuSide_->ctx->deviceName(), gpuSide_->swapchain->presentPath());
    if (automation_.benchRan())
      std::printf("viewport: %d scene passes, %d frames showed the kept image (%s)\n", scenePasses_ - benchScenePasses_,
                  keptFrames_ - benchKeptFrames_, gpuSide_->viewportImage ? "kept viewport image" : "drawn every frame");
    gpuSide_->ctx->waitIdle();
    if (gpuSide_->ctx->validationEnabled() && gpuSide_->ctx->validationErrorCount() > 0) {
      std::fprintf(stderr, "animorph: %u Vulkan validation error(s)\n", gpuSide_->ctx->validationErrorCount());
      exitCode_ = 3;
    }
  }
  ui_.savePreferences();
  gpuSide_.reset();
  closeEditorWindow(window_);
  return exitCode_;
}

}  // namespace

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
  Editor editor(args, window, ss, std::move(*gpuR), clock);
  clock.startFrames();
  while (editor.frame()) {
  }
  return editor.finish();
}
