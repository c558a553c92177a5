#pragma once
// Dear ImGui on GLFW + Vulkan: the GLFW backend (1.86) for input, and our own
// renderer for the draw data in the swapchain's render pass. Ours, not the 1.86
// Vulkan backend, because the backend's font sampler is bilinear and fixed in
// its descriptor set layout: on CPU devices (lavapipe) the UI's fragments were
// about half of an idle editor frame. Here the atlas is alpha only and sampled
// nearest (exact for text, drawn at 1:1 on whole pixels), and lines are drawn as
// geometry (no baked line textures).
#include <memory>
#include <vector>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "gpu/vulkan/image.h"
#include "shared_constants.h"
#include "gpu/present/swapchain.h"
#include "core/util/result.h"

namespace animorph {

class ImGuiVulkan {
 public:
  // Creates the ImGui context (if none), initialises the GLFW backend, builds
  // the renderer for swapchain's render pass and uploads the font atlas.
  static Result<std::unique_ptr<ImGuiVulkan>> create(gpu::Context& ctx, gpu::Swapchain& swapchain);
  ~ImGuiVulkan();
  ImGuiVulkan(const ImGuiVulkan&) = delete;
  ImGuiVulkan& operator=(const ImGuiVulkan&) = delete;

  // GLFW backend NewFrame + ImGui::NewFrame.
  void newFrame();
  // Records ImGui's draw data (after ImGui::Render) into cmd, inside the render
  // pass of frame-in-flight `slot` (gpu::Frame::slot), whose previous commands
  // have completed. Errors: vertex or index buffer allocation.
  Status record(VkCommandBuffer cmd, uint32_t slot);

 private:
  struct Slot {
    gpu::Buffer vertices, indices;
  };
  ImGuiVulkan(gpu::Context& ctx) : ctx_(ctx) {}
  Status init(VkRenderPass renderPass);
  Status uploadAtlas();

  gpu::Context& ctx_;
  bool glfwInit_ = false;
  gpu::Image atlas_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  Slot slots_[gpu::kFramesInFlight];
};

}  // namespace animorph
