#pragma once
// 2D images with their own memory and a view (plain struct + free functions).
#include <vulkan/vulkan.h>

#include "gpu/vulkan/context.h"

namespace animorph::gpu {

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
};

// A device-local 2D image (one mip, one layer, optimal tiling) and a view of
// aspect. Errors: unsupported format/usage, allocation failure.
Result<Image> createImage(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect);

// A device-local image for sampling, filled with bytes (rows top to bottom, tightly packed)
// through a staging buffer (waits for the copy), left in SHADER_READ_ONLY_OPTIMAL for
// fragment shaders. Errors: as createImage, the staging buffer, the submission.
Result<Image> createSampledImage(Context& ctx, VkExtent2D extent, VkFormat format, const void* data, VkDeviceSize bytes);

// Frees image (no-op on an empty one) and resets it to empty.
void destroyImage(VkDevice device, Image& image);

}  // namespace animorph::gpu
