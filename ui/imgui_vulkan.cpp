#include "imgui_vulkan.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace animorph {
namespace {
void checkVk(VkResult r) {
  if (r != VK_SUCCESS) std::fprintf(stderr, "animorph: ImGui Vulkan backend: VkResult %d\n", static_cast<int>(r));
}

// ImGui 1.86 keeps keys as up/down state read once per frame, so a key pressed
// and released between two frames (a quick tap while a slow frame renders, or
// synthetic input) would never be seen. Releases that follow a press since the
// last frame are held back until ImGui has seen that frame's keys down once.
struct DeferredRelease {
  int key, scancode, mods;
};
std::vector<int> g_pressedSinceFrame;                 // presses since the last NewFrame
std::vector<DeferredRelease> g_deferredReleases;      // their releases, for the next frame
std::vector<DeferredRelease> g_releasesForThisFrame;  // deferred by the previous frame

void keyCallback(GLFWwindow* window, int key, int scancode, int action, int mods) {
  // Once a key went down since the last frame, every release waits for the
  // next frame, so the frame sees the whole chord (Ctrl+Shift+Z) as it was.
  if (action == GLFW_RELEASE && !g_pressedSinceFrame.empty()) {
    g_deferredReleases.push_back({key, scancode, mods});
    return;
  }
  if (action == GLFW_PRESS) g_pressedSinceFrame.push_back(key);
  ImGui_ImplGlfw_KeyCallback(window, key, scancode, action, mods);
}
}  // namespace

Result<std::unique_ptr<ImGuiVulkan>> ImGuiVulkan::create(gpu::Context& ctx, gpu::Swapchain& swapchain) {
  std::unique_ptr<ImGuiVulkan> self(new ImGuiVulkan(ctx, swapchain));
  if (!ImGui::GetCurrentContext()) ImGui::CreateContext();
  if (!ImGui_ImplGlfw_InitForVulkan(ctx.window(), true)) return Error{"ImGui: GLFW backend initialisation failed"};
  self->glfwInit_ = true;
  glfwSetKeyCallback(ctx.window(), keyCallback);  // forwards to ImGui's (see keyCallback)
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
  // The previous frame saw its keys down (and its shortcuts ran with the
  // modifiers still held): deliver the releases it held back, except for keys
  // pressed again since.
  for (const auto& r : g_releasesForThisFrame)
    if (std::find(g_pressedSinceFrame.begin(), g_pressedSinceFrame.end(), r.key) == g_pressedSinceFrame.end())
      ImGui_ImplGlfw_KeyCallback(ctx_.window(), r.key, r.scancode, GLFW_RELEASE, r.mods);
  g_releasesForThisFrame.swap(g_deferredReleases);
  g_deferredReleases.clear();
  g_pressedSinceFrame.clear();
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiVulkan::record(VkCommandBuffer cmd) { ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd); }

}  // namespace animorph
