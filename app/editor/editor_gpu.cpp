#include "editor_gpu.h"

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
  g->meshes = std::make_unique<gpu::MeshCache>(*g->ctx);
  g->blobPreviews = std::make_unique<gpu::BlobPreviewSet>(*g->ctx);
  g->standinBindings = std::make_unique<gpu::StandinBindingCache>(*g->ctx);
  g->morphPreview = std::make_unique<gpu::ImplicitPreview>(*g->ctx);
  return g;
}

}  // namespace animorph
