#pragma once
// The one render pass shape every scene target uses: colour + depth, one subpass.
#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

// Colour (cleared, stored, ending in colorFinalLayout: PRESENT_SRC_KHR for a
// swapchain, TRANSFER_SRC_OPTIMAL for an offscreen target that is read back)
// and depth (cleared, not stored). loadColor: the colour attachment is loaded instead of cleared and
// starts in COLOR_ATTACHMENT_OPTIMAL (a frame whose kept viewport image was copied in before the
// pass), and depth is neither cleared nor stored (DONT_CARE: only pipelines that test no depth, the
// UI's, may draw in it); the pass stays compatible with the cleared one (same formats), so pipelines
// made for one draw in the other. Errors: Vulkan failures.
Result<VkRenderPass> createSceneRenderPass(VkDevice device, VkFormat colorFormat, VkFormat depthFormat,
                                           VkImageLayout colorFinalLayout, bool loadColor = false);

// A framebuffer of renderPass (one made by createSceneRenderPass) over colorView and depthView,
// extent wide and high, one layer. Errors: Vulkan failures. The caller destroys it.
Result<VkFramebuffer> createSceneFramebuffer(VkDevice device, VkRenderPass renderPass, VkImageView colorView,
                                             VkImageView depthView, VkExtent2D extent);

// Begins renderPass (one made by createSceneRenderPass) on framebuffer over its whole extent, inline
// contents, the colour cleared to clearColor (r, g, b, a) and depth to 1 (a pass that loads its colour
// ignores the colour clear). The caller ends the pass.
void beginScenePass(VkCommandBuffer cmd, VkRenderPass renderPass, VkFramebuffer framebuffer, VkExtent2D extent,
                    const float clearColor[4]);

}  // namespace animorph::gpu
