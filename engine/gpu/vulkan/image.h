#pragma once
// 2D images with their own memory and a view (plain struct + free functions).
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/vulkan/context.h"

namespace animorph::gpu {

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
  uint32_t mipLevels = 1;
};

// A device-local 2D image (mipLevels levels, one layer, optimal tiling) and a view of aspect
// over every level. Errors: unsupported format/usage, allocation failure.
Result<Image> createImage(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect, uint32_t mipLevels = 1);

// The bytes of one mip level of a sampled image: rows top to bottom, tightly packed.
struct ImageLevel {
  VkExtent2D extent{0, 0};
  const void* data = nullptr;
  VkDeviceSize bytes = 0;
};

// A device-local image for sampling with levels.size() mip levels (levels[0] the full image,
// each next one smaller as the caller made it), filled through one staging buffer (waits for
// the copy), left in SHADER_READ_ONLY_OPTIMAL for fragment shaders. Errors: no level, as
// createImage, the staging buffer, the submission.
Result<Image> createSampledImage(Context& ctx, VkFormat format, const std::vector<ImageLevel>& levels);

// A device-local image for sampling, filled with bytes (rows top to bottom, tightly packed)
// through a staging buffer (waits for the copy), left in SHADER_READ_ONLY_OPTIMAL for
// fragment shaders. Errors: as createImage, the staging buffer, the submission.
Result<Image> createSampledImage(Context& ctx, VkExtent2D extent, VkFormat format, const void* data, VkDeviceSize bytes);

// Frees image (no-op on an empty one) and resets it to empty.
void destroyImage(VkDevice device, Image& image);

}  // namespace animorph::gpu
