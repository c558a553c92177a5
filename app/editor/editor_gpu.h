#pragma once
// The editor's Vulkan side: the device, the swapchain, the renderers and the GPU caches and
// previews, made together and, after a lost device, remade together (docs/rendering.md, "A lost
// device"). The document, the UI state and ImGui's context live outside and survive.
#include <memory>

#include "blob_preview_set.h"
#include "context.h"
#include "implicit_preview.h"
#include "imgui_vulkan.h"
#include "mesh_cache.h"
#include "scene_renderer.h"
#include "standin_binding_cache.h"
#include "swapchain.h"

struct GLFWwindow;

namespace animorph {

struct EditorGpu {
  // Destroyed in reverse: previews and caches, then the renderers, the swapchain, the device.
  std::unique_ptr<gpu::Context> ctx;
  std::unique_ptr<gpu::Swapchain> swapchain;
  std::unique_ptr<gpu::SceneRenderer> renderer;
  std::unique_ptr<ImGuiVulkan> imgui;  // needs ImGui's context
  std::unique_ptr<gpu::MeshCache> meshes;
  std::unique_ptr<gpu::BlobPreviewSet> blobPreviews;
  std::unique_ptr<gpu::StandinBindingCache> standinBindings;
  std::unique_ptr<gpu::ImplicitPreview> morphPreview;  // the morph's B->C stage
};

// Errors: no usable device ("no usable Vulkan device: ..."), or what failed to be made.
Result<std::unique_ptr<EditorGpu>> createEditorGpu(GLFWwindow* window, const gpu::SwapchainSettings& settings);

}  // namespace animorph
