#pragma once
// Dear ImGui on GLFW + Vulkan (1.86 backends): initialisation, font upload,
// per-frame begin, and recording the draw data into the swapchain's render pass.
#include <memory>

#include "context.h"
#include "swapchain.h"
#include "util/result.h"

namespace animorph {

class ImGuiVulkan {
 public:
  // Creates the ImGui context (if none), initialises the GLFW and Vulkan
  // backends for swapchain's render pass and uploads the font atlas.
  static Result<std::unique_ptr<ImGuiVulkan>> create(gpu::Context& ctx, gpu::Swapchain& swapchain);
  ~ImGuiVulkan();
  ImGuiVulkan(const ImGuiVulkan&) = delete;
  ImGuiVulkan& operator=(const ImGuiVulkan&) = delete;

  // Backend NewFrame + ImGui::NewFrame (follows swapchain recreation).
  void newFrame();
  // Records ImGui's draw data (after ImGui::Render) into cmd.
  void record(VkCommandBuffer cmd);

 private:
  ImGuiVulkan(gpu::Context& ctx, gpu::Swapchain& swapchain) : ctx_(ctx), swapchain_(swapchain) {}
  gpu::Context& ctx_;
  gpu::Swapchain& swapchain_;
  uint32_t generation_ = 0;
  bool glfwInit_ = false, vulkanInit_ = false;
};

}  // namespace animorph
