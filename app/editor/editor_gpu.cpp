#include "app/editor/editor_gpu.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gpu/present/rgba_image.h"
#include "gpu/render/scene_fingerprint.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph {

Result<std::unique_ptr<EditorGpu>> createEditorGpu(GLFWwindow* window, const gpu::SwapchainSettings& settings) {
  auto g = std::make_unique<EditorGpu>();
  gpu::ContextSettings cs;
  cs.window = window;
  auto ctx = gpu::Context::create(cs);
  if (!ctx) return Error{"no usable Vulkan device: " + ctx.error()};
  g->ctx = std::move(*ctx);
  auto swapchain = gpu::Swapchain::create(*g->ctx, settings);
  if (!swapchain) return Error{swapchain.error()};
  g->swapchain = std::move(*swapchain);
  auto renderer = gpu::SceneRenderer::create(*g->ctx, g->swapchain->renderPass());
  if (!renderer) return Error{renderer.error()};
  g->renderer = std::move(*renderer);
  auto imgui = ImGuiVulkan::create(*g->ctx, *g->swapchain);
  if (!imgui) return Error{imgui.error()};
  g->imgui = std::move(*imgui);
  const char* keep = std::getenv("ANIMORPH_VIEWPORT_IMAGE");  // "off": the scene drawn in every frame (comparisons)
  if (!(keep && std::strcmp(keep, "off") == 0) && g->swapchain->underlaySupported()) {
    auto vi = gpu::ViewportImage::create(*g->ctx, g->swapchain->colorFormat());
    if (!vi) return Error{vi.error()};
    g->viewportImage = std::move(*vi);
  }
  g->meshes = std::make_unique<gpu::MeshCache>(*g->ctx);
  g->blobPreviews = std::make_unique<gpu::BlobPreviewSet>(*g->ctx);
  g->standinBindings = std::make_unique<gpu::StandinBindingCache>(*g->ctx);
  g->morphPreview = std::make_unique<gpu::ImplicitPreview>(*g->ctx);
  return g;
}

Result<std::string> recoverLostDevice(GLFWwindow* window, const gpu::SwapchainSettings& settings, Document& doc,
                                      double nowSec, std::unique_ptr<EditorGpu>& gpuSide) {
  // Written now, or by the periodic autosave since the last edit: either way the work is safe.
  const bool autosaved = doc.autosaveIfDue(nowSec, 0.0) || doc.autosaveIsCurrent();
  std::fprintf(stderr, "animorph: the GPU device was lost; recreating the renderer%s\n",
               autosaved ? (" (work autosaved to " + doc.autosavePath() + ")").c_str() : "");
  gpuSide.reset();
  gpu::clearDeviceLost();
  auto again = createEditorGpu(window, settings);
  if (!again) {
    std::fprintf(stderr, "animorph: cannot recreate the renderer: %s; quitting%s\n", again.error().c_str(),
                 doc.dirty() ? " (the autosave is offered when the project is opened again)" : "");
    return Error{again.error()};
  }
  gpuSide = std::move(*again);
  return std::string("The GPU device was lost; the renderer was recreated") + (autosaved ? " (work autosaved)" : "");
}

namespace {

// The scene into the frame's viewport rectangle: rendered into the kept image when it changed, then
// the kept image copied under the UI; without a kept image, rendered into the frame's render pass.
// Begins the frame's render pass.
void recordViewport(EditorGpu& g, const gpu::Frame& f, const gpu::ViewportRect& rect, const OrbitCamera& camera,
                    const gpu::Scene& scene, PresentedFrame& r) {
  if (rect.width == 0 || rect.height == 0) {
    g.swapchain->beginPass(nullptr);
    return;
  }
  if (g.viewportImage) {
    const std::optional<uint64_t> fp = gpu::sceneFingerprint(scene, camera, rect.width, rect.height);
    const VkExtent2D kept = g.viewportImage->extent();
    r.sceneKept = fp && g.viewportImage->valid() && g.viewportFingerprint == fp && kept.width == rect.width &&
                  kept.height == rect.height;
    if (!r.sceneKept) {
      Status st = Status::success();
      Status made = g.viewportImage->render(f.cmd, rect.width, rect.height, [&](VkCommandBuffer cmd) {
        st = g.renderer->record(cmd, f.serial, {0, 0, rect.width, rect.height}, camera, scene);
      });
      if (!made) std::fprintf(stderr, "animorph: %s\n", made.error().c_str());
      if (!st) std::fprintf(stderr, "animorph: %s\n", st.error().c_str());
      g.viewportFingerprint = made && st ? fp : std::nullopt;
      r.scenePass = made.ok();
    }
    if (g.viewportImage->valid()) {
      const gpu::FrameUnderlay u = g.viewportImage->underlay(rect.x, rect.y);
      g.swapchain->beginPass(&u);
      return;
    }
  }
  g.swapchain->beginPass(nullptr);
  Status st = g.renderer->record(f.cmd, f.serial, rect, camera, scene);
  if (!st) std::fprintf(stderr, "animorph: %s\n", st.error().c_str());
  r.scenePass = true;
}

}  // namespace

PresentedFrame presentFrame(EditorGpu& g, const ViewportRect& viewport, const OrbitCamera& camera,
                            const gpu::Scene& scene, const std::string& capturePath) {
  PresentedFrame r;
  gpu::Frame f;
  r.status = g.swapchain->acquireFrame(f);
  if (r.status == gpu::FrameStatus::Failed) {
    std::fprintf(stderr, "animorph: %s\n", g.swapchain->lastError().c_str());
    return r;
  }
  if (r.status != gpu::FrameStatus::Ready) return r;
  const ImGuiIO& io = ImGui::GetIO();
  const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
  gpu::ViewportRect rect;
  rect.x = static_cast<int32_t>(viewport.min.x * sx);
  rect.y = static_cast<int32_t>(viewport.min.y * sy);
  rect.width = static_cast<uint32_t>(std::max(0.0f, viewport.size.x * sx));
  rect.height = static_cast<uint32_t>(std::max(0.0f, viewport.size.y * sy));
  rect.width = std::min(rect.width, f.extent.width - std::min<uint32_t>(f.extent.width, rect.x));
  rect.height = std::min(rect.height, f.extent.height - std::min<uint32_t>(f.extent.height, rect.y));
  recordViewport(g, f, rect, camera, scene, r);
  Status ui = g.imgui->record(f.cmd, f.slot);
  if (!ui) std::fprintf(stderr, "animorph: %s\n", ui.error().c_str());
  Status st = g.swapchain->endFrame();
  if (!st) std::fprintf(stderr, "animorph: %s\n", st.error().c_str());
  if (auto img = g.swapchain->takeCapture(); img && !capturePath.empty()) {
    Status w = gpu::writePng(capturePath, *img);
    if (!w) std::fprintf(stderr, "animorph: %s\n", w.error().c_str());
    r.captured = true;
  }
  return r;
}

}  // namespace animorph
