#include "imgui_vulkan.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <cstdio>

namespace animorph {
namespace {
void checkVk(VkResult r) {
  if (r != VK_SUCCESS) std::fprintf(stderr, "animorph: ImGui Vulkan backend: VkResult %d\n", static_cast<int>(r));
}
}  // namespace

Result<std::unique_ptr<ImGuiVulkan>> ImGuiVulkan::create(gpu::Context& ctx, gpu::Swapchain& swapchain) {
  std::unique_ptr<ImGuiVulkan> self(new ImGuiVulkan(ctx, swapchain));
  if (!ImGui::GetCurrentContext()) ImGui::CreateContext();
  if (!ImGui_ImplGlfw_InitForVulkan(ctx.window(), true)) return Error{"ImGui: GLFW backend initialisation failed"};
  self->glfwInit_ = true;
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = ctx.instance();
  info.PhysicalDevice = ctx.physicalDevice();
  info.Device = ctx.device();
  info.QueueFamily = ctx.queueFamily();
  info.Queue = ctx.queue();
  info.DescriptorPool = ctx.uiDescriptorPool();
  info.MinImageCount = std::max(2u, swapchain.minImageCount());
  info.ImageCount = std::max(info.MinImageCount, swapchain.imageCount());
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkVk;
  if (!ImGui_ImplVulkan_Init(&info, swapchain.renderPass())) return Error{"ImGui: Vulkan backend initialisation failed"};
  self->vulkanInit_ = true;
  self->generation_ = swapchain.generation();
  Status st = ctx.submitImmediate([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  if (!st) return Error{"ImGui: font upload failed: " + st.error()};
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  return self;
}

ImGuiVulkan::~ImGuiVulkan() {
  ctx_.waitIdle();
  if (vulkanInit_) ImGui_ImplVulkan_Shutdown();
  if (glfwInit_) ImGui_ImplGlfw_Shutdown();
}

void ImGuiVulkan::newFrame() {
  if (swapchain_.generation() != generation_) {
    generation_ = swapchain_.generation();
    ImGui_ImplVulkan_SetMinImageCount(std::max(2u, swapchain_.minImageCount()));
  }
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiVulkan::record(VkCommandBuffer cmd) { ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd); }

}  // namespace animorph
