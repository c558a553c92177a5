#include "gpu/present/imgui_vulkan.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "gpu/vulkan/graphics_pipeline.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph {
namespace {
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

// Vertex layout: ImDrawVert (pos, uv, col).
static_assert(sizeof(ImDrawVert) == 20, "ImDrawVert is pos, uv, col");

// A host-visible buffer of at least `bytes` for usage (grown by half again, so a
// growing UI does not reallocate every frame).
Status ensureHostBuffer(gpu::Context& ctx, gpu::Buffer& b, VkDeviceSize bytes, VkBufferUsageFlags usage) {
  if (b.buffer && b.size >= bytes) return Status::success();
  gpu::destroyBuffer(ctx.device(), b);
  Result<gpu::Buffer> r = gpu::createHostBuffer(ctx, std::max<VkDeviceSize>(bytes + bytes / 2, 64 * 1024), usage);
  if (!r) return Error{"ImGui: " + r.error()};
  b = *r;
  return Status::success();
}
}  // namespace

Result<std::unique_ptr<ImGuiVulkan>> ImGuiVulkan::create(gpu::Context& ctx, gpu::Swapchain& swapchain) {
  std::unique_ptr<ImGuiVulkan> self(new ImGuiVulkan(ctx));
  if (!ImGui::GetCurrentContext()) ImGui::CreateContext();
  if (!ImGui_ImplGlfw_InitForVulkan(ctx.window(), true)) return Error{"ImGui: GLFW backend initialisation failed"};
  self->glfwInit_ = true;
  glfwSetKeyCallback(ctx.window(), keyCallback);  // forwards to ImGui's (see keyCallback)
  ImGuiIO& io = ImGui::GetIO();
  io.BackendRendererName = "animorph_vulkan";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // 16-bit indices, vertex offsets per command
  Status st = self->init(swapchain.renderPass());
  if (st) st = self->uploadAtlas();
  if (!st) return Error{st.error()};
  return self;
}

Status ImGuiVulkan::init(VkRenderPass renderPass) {
  VkDevice dev = ctx_.device();
  VkSamplerCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = 0.0f;
  AM_VK_TRY(vkCreateSampler(dev, &si, nullptr, &sampler_), "ImGui: vkCreateSampler");
  VkDescriptorSetLayoutBinding binding{};
  binding.binding = 0;
  binding.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  binding.descriptorCount = 1;
  binding.stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
  VkDescriptorSetLayoutCreateInfo dli{};
  dli.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  dli.bindingCount = 1;
  dli.pBindings = &binding;
  AM_VK_TRY(vkCreateDescriptorSetLayout(dev, &dli, nullptr, &setLayout_), "ImGui: vkCreateDescriptorSetLayout");
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = ctx_.uiDescriptorPool();
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &setLayout_;
  AM_VK_TRY(vkAllocateDescriptorSets(dev, &ai, &set_), "ImGui: vkAllocateDescriptorSets");
  VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, 16};
  VkPipelineLayoutCreateInfo pli{};
  pli.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout_;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &push;
  AM_VK_TRY(vkCreatePipelineLayout(dev, &pli, nullptr, &layout_), "ImGui: vkCreatePipelineLayout");

  gpu::GraphicsPipelineDesc d;
  d.vert = "ui.vert";
  d.frag = "ui.frag";
  d.bindings = {{0, sizeof(ImDrawVert), VK_VERTEX_INPUT_RATE_VERTEX}};
  d.attributes = {{0, 0, VK_FORMAT_R32G32_SFLOAT, static_cast<uint32_t>(offsetof(ImDrawVert, pos))},
                  {1, 0, VK_FORMAT_R32G32_SFLOAT, static_cast<uint32_t>(offsetof(ImDrawVert, uv))},
                  {2, 0, VK_FORMAT_R8G8B8A8_UNORM, static_cast<uint32_t>(offsetof(ImDrawVert, col))}};
  d.depthTest = d.depthWrite = false;  // the UI draws over the viewport
  d.blend = gpu::BlendMode::StraightAlpha;
  Result<VkPipeline> p = gpu::createGraphicsPipeline(dev, renderPass, layout_, d);
  if (!p) return Error{"ImGui: " + p.error()};
  pipeline_ = *p;
  return Status::success();
}

Status ImGuiVulkan::uploadAtlas() {
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Flags |= ImFontAtlasFlags_NoBakedLines;  // lines as geometry: the atlas is sampled nearest
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsAlpha8(&pixels, &w, &h);
  if (!pixels || w <= 0 || h <= 0) return Error{"ImGui: the font atlas could not be built"};
  const VkDeviceSize bytes = VkDeviceSize(w) * VkDeviceSize(h);
  Result<gpu::Image> img = gpu::createSampledImage(ctx_, VK_FORMAT_R8_UNORM, {{VkExtent2D{uint32_t(w), uint32_t(h)}, pixels, bytes}});
  if (!img) return Error{"ImGui: font atlas: " + img.error()};
  atlas_ = *img;
  VkDescriptorImageInfo ii{sampler_, atlas_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet wr{};
  wr.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  wr.dstSet = set_;
  wr.descriptorCount = 1;
  wr.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  wr.pImageInfo = &ii;
  vkUpdateDescriptorSets(ctx_.device(), 1, &wr, 0, nullptr);
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(set_));
  io.Fonts->ClearTexData();  // the pixels live on the device now
  return Status::success();
}

ImGuiVulkan::~ImGuiVulkan() {
  ctx_.waitIdle();
  VkDevice dev = ctx_.device();
  for (Slot& s : slots_) {
    gpu::destroyBuffer(dev, s.vertices);
    gpu::destroyBuffer(dev, s.indices);
  }
  if (pipeline_) vkDestroyPipeline(dev, pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
  if (set_) vkFreeDescriptorSets(dev, ctx_.uiDescriptorPool(), 1, &set_);
  if (setLayout_) vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
  if (sampler_) vkDestroySampler(dev, sampler_, nullptr);
  gpu::destroyImage(dev, atlas_);
  if (glfwInit_) ImGui_ImplGlfw_Shutdown();
}

void ImGuiVulkan::newFrame() {
  // The previous frame saw its keys down (and its shortcuts ran with the
  // modifiers still held): deliver the releases it held back, except for keys
  // pressed again since.
  for (const auto& r : g_releasesForThisFrame)
    if (std::find(g_pressedSinceFrame.begin(), g_pressedSinceFrame.end(), r.key) == g_pressedSinceFrame.end())
      ImGui_ImplGlfw_KeyCallback(ctx_.window(), r.key, r.scancode, GLFW_RELEASE, r.mods);
  g_releasesForThisFrame.swap(g_deferredReleases);
  g_deferredReleases.clear();
  g_pressedSinceFrame.clear();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

Status ImGuiVulkan::record(VkCommandBuffer cmd, uint32_t slot) {
  const ImDrawData* dd = ImGui::GetDrawData();
  if (!dd || dd->CmdListsCount == 0) return Status::success();
  const float fbW = dd->DisplaySize.x * dd->FramebufferScale.x, fbH = dd->DisplaySize.y * dd->FramebufferScale.y;
  if (fbW <= 0.0f || fbH <= 0.0f || dd->TotalVtxCount == 0) return Status::success();
  Slot& s = slots_[slot % gpu::kFramesInFlight];
  Status st = ensureHostBuffer(ctx_, s.vertices, VkDeviceSize(dd->TotalVtxCount) * sizeof(ImDrawVert),
                               VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  if (st) st = ensureHostBuffer(ctx_, s.indices, VkDeviceSize(dd->TotalIdxCount) * sizeof(ImDrawIdx),
                                VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  if (!st) return st;
  auto* vtx = static_cast<ImDrawVert*>(s.vertices.mapped);
  auto* idx = static_cast<ImDrawIdx*>(s.indices.mapped);
  for (int n = 0; n < dd->CmdListsCount; ++n) {
    const ImDrawList* list = dd->CmdLists[n];
    std::memcpy(vtx, list->VtxBuffer.Data, size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert));
    std::memcpy(idx, list->IdxBuffer.Data, size_t(list->IdxBuffer.Size) * sizeof(ImDrawIdx));
    vtx += list->VtxBuffer.Size;
    idx += list->IdxBuffer.Size;
  }

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &s.vertices.buffer, &zero);
  vkCmdBindIndexBuffer(cmd, s.indices.buffer, 0, sizeof(ImDrawIdx) == 2 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32);
  VkViewport viewport{0.0f, 0.0f, fbW, fbH, 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  // Display pixels -> clip space.
  const float scale[2] = {2.0f / dd->DisplaySize.x, 2.0f / dd->DisplaySize.y};
  const float push[4] = {scale[0], scale[1], -1.0f - dd->DisplayPos.x * scale[0], -1.0f - dd->DisplayPos.y * scale[1]};
  vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), push);

  const ImVec2 off = dd->DisplayPos, sc = dd->FramebufferScale;
  uint32_t vtxBase = 0, idxBase = 0;
  for (int n = 0; n < dd->CmdListsCount; ++n) {
    const ImDrawList* list = dd->CmdLists[n];
    for (int c = 0; c < list->CmdBuffer.Size; ++c) {
      const ImDrawCmd& pc = list->CmdBuffer[c];
      if (pc.UserCallback) {
        // ImDrawCallback_ResetRenderState is the only callback ImGui itself emits; the editor adds none.
        if (pc.UserCallback != ImDrawCallback_ResetRenderState) pc.UserCallback(list, &pc);
        continue;
      }
      // Clip rectangle in framebuffer pixels, clamped to it.
      float x0 = std::max(0.0f, (pc.ClipRect.x - off.x) * sc.x), y0 = std::max(0.0f, (pc.ClipRect.y - off.y) * sc.y);
      float x1 = std::min(fbW, (pc.ClipRect.z - off.x) * sc.x), y1 = std::min(fbH, (pc.ClipRect.w - off.y) * sc.y);
      if (x1 <= x0 || y1 <= y0) continue;
      VkRect2D scissor{{int32_t(x0), int32_t(y0)}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
      vkCmdSetScissor(cmd, 0, 1, &scissor);
      vkCmdDrawIndexed(cmd, pc.ElemCount, 1, pc.IdxOffset + idxBase, int32_t(pc.VtxOffset + vtxBase), 0);
    }
    vtxBase += uint32_t(list->VtxBuffer.Size);
    idxBase += uint32_t(list->IdxBuffer.Size);
  }
  return Status::success();
}

}  // namespace animorph
