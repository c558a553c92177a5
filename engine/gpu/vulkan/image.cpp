#include "gpu/vulkan/image.h"

#include <cstring>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

namespace {

// Copies src (the levels at their offsets) into the image's levels and leaves it shader-readable.
Status copyToImage(Context& ctx, VkBuffer src, VkImage dst, const std::vector<ImageLevel>& levels,
                   const std::vector<VkDeviceSize>& offsets) {
  return ctx.submitImmediate([&](VkCommandBuffer cmd) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = dst;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, uint32_t(levels.size()), 0, 1};
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
    std::vector<VkBufferImageCopy> regions(levels.size());
    for (size_t l = 0; l < levels.size(); ++l) {
      regions[l].bufferOffset = offsets[l];
      regions[l].imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, uint32_t(l), 0, 1};
      regions[l].imageExtent = {levels[l].extent.width, levels[l].extent.height, 1};
    }
    vkCmdCopyBufferToImage(cmd, src, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()),
                           regions.data());
    b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
  });
}

}  // namespace

Result<Image> createImage(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect, uint32_t mipLevels) {
  Image img;
  img.format = format;
  img.extent = extent;
  img.mipLevels = mipLevels;
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = format;
  ici.extent = {extent.width, extent.height, 1};
  ici.mipLevels = mipLevels;
  ici.arrayLayers = 1;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = usage;
  ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  const std::string what = "image " + std::to_string(extent.width) + "x" + std::to_string(extent.height);
  AM_VK_TRY(vkCreateImage(ctx.device(), &ici, nullptr, &img.image), "vkCreateImage (" + what + ")");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device(), img.image, &req);
  uint32_t type = ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type == UINT32_MAX) type = ctx.findMemoryType(req.memoryTypeBits, 0);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = type;
  VkResult r = type == UINT32_MAX ? VK_ERROR_OUT_OF_DEVICE_MEMORY : vkAllocateMemory(ctx.device(), &mai, nullptr, &img.memory);
  if (r == VK_SUCCESS) r = vkBindImageMemory(ctx.device(), img.image, img.memory, 0);
  if (r == VK_SUCCESS) {
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = img.image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format;
    vci.subresourceRange = {aspect, 0, mipLevels, 0, 1};
    r = vkCreateImageView(ctx.device(), &vci, nullptr, &img.view);
  }
  if (r != VK_SUCCESS) {
    destroyImage(ctx.device(), img);
    return vkError("allocating " + what, r);
  }
  return img;
}

void destroyImage(VkDevice device, Image& img) {
  if (img.view) vkDestroyImageView(device, img.view, nullptr);
  if (img.image) vkDestroyImage(device, img.image, nullptr);
  if (img.memory) vkFreeMemory(device, img.memory, nullptr);
  img = Image{};
}

Result<Image> createSampledImage(Context& ctx, VkFormat format, const std::vector<ImageLevel>& levels) {
  if (levels.empty()) return Error{"a sampled image needs at least one level"};
  std::vector<VkDeviceSize> offsets(levels.size());
  VkDeviceSize bytes = 0;
  for (size_t l = 0; l < levels.size(); ++l) {
    offsets[l] = bytes;
    bytes += (levels[l].bytes + 15) & ~VkDeviceSize(15);  // every level's copy starts 16-byte aligned
  }
  Result<Image> img = createImage(ctx, levels[0].extent, format,
                                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                                  uint32_t(levels.size()));
  if (!img) return img;
  Result<Buffer> staging = createHostBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  if (!staging) {
    destroyImage(ctx.device(), *img);
    return Error{staging.error()};
  }
  for (size_t l = 0; l < levels.size(); ++l)
    std::memcpy(static_cast<char*>(staging->mapped) + offsets[l], levels[l].data, levels[l].bytes);
  Status st = copyToImage(ctx, staging->buffer, img->image, levels, offsets);
  destroyBuffer(ctx.device(), *staging);
  if (!st) {
    destroyImage(ctx.device(), *img);
    return Error{"upload failed: " + st.error()};
  }
  return img;
}

}  // namespace animorph::gpu
