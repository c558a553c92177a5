#pragma once
// One graphics pipeline over the embedded shaders, with the state every
// renderer here shares: dynamic viewport and scissor, one sample, one colour
// attachment, counter-clockwise front faces. Used by the scene renderer and the
// UI renderer (engine/gpu/present/imgui_vulkan.cpp).
#include <vector>

#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

enum class BlendMode {
  None,
  OverOpaque,     // colour over by source alpha; the target's alpha is kept (the scene's overlays)
  StraightAlpha,  // colour over by source alpha; alpha = a + (1 - a) dst (as Dear ImGui's backends)
};

struct GraphicsPipelineDesc {
  const char* vert = nullptr;  // embedded shader names ("mesh.vert")
  const char* frag = nullptr;
  std::vector<VkVertexInputBindingDescription> bindings;
  std::vector<VkVertexInputAttributeDescription> attributes;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
  bool depthTest = true;  // LESS_OR_EQUAL
  bool depthWrite = true;
  BlendMode blend = BlendMode::None;
  VkCullModeFlags cull = VK_CULL_MODE_NONE;
  const VkSpecializationInfo* specialization = nullptr;  // both stages' specialisation constants (null: defaults)
};

// Errors: unknown shader, Vulkan failure ("pipeline VERT + FRAG: VK_ERROR_...").
Result<VkPipeline> createGraphicsPipeline(VkDevice device, VkRenderPass pass, VkPipelineLayout layout,
                                          const GraphicsPipelineDesc& d);

}  // namespace animorph::gpu
