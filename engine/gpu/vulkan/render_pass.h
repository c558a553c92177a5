#pragma once
// The one render pass shape every scene target uses: colour + depth, one subpass.
#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

// Colour (cleared, stored, ending in colorFinalLayout: PRESENT_SRC_KHR for a
// swapchain, TRANSFER_SRC_OPTIMAL for an offscreen target that is read back)
// and depth (cleared, not stored). Errors: Vulkan failures.
Result<VkRenderPass> createSceneRenderPass(VkDevice device, VkFormat colorFormat, VkFormat depthFormat,
                                           VkImageLayout colorFinalLayout);

}  // namespace animorph::gpu
