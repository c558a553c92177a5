#include "gpu/vulkan/buffer.h"

#include <cstdlib>
#include <cstring>

#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

Result<Buffer> createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                            VkMemoryPropertyFlags props) {
  // Testing the out-of-memory paths for real: ANIMORPH_DEBUG_GPU_BUFFER_LIMIT_KB
  // refuses device-local storage buffers (compute data) larger than the limit,
  // as a device out of memory would.
  if (const char* limit = std::getenv("ANIMORPH_DEBUG_GPU_BUFFER_LIMIT_KB");
      limit && (usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && !(props & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) &&
      size > VkDeviceSize(std::atoll(limit)) * 1024)
    return vkError("allocating " + std::to_string(size) + " bytes of buffer memory (ANIMORPH_DEBUG_GPU_BUFFER_LIMIT_KB=" +
                       limit + ")",
                   VK_ERROR_OUT_OF_DEVICE_MEMORY);
  Buffer b;
  b.size = size;
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size;
  bci.usage = usage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  AM_VK_TRY(vkCreateBuffer(ctx.device(), &bci, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), b.buffer, &req);
  uint32_t type = ctx.findMemoryType(req.memoryTypeBits, props);
  if (type == UINT32_MAX) {
    destroyBuffer(ctx.device(), b);
    return Error{"no memory type for a buffer of " + std::to_string(size) + " bytes with the requested properties"};
  }
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = type;
  VkResult r = vkAllocateMemory(ctx.device(), &mai, nullptr, &b.memory);
  if (r == VK_SUCCESS) r = vkBindBufferMemory(ctx.device(), b.buffer, b.memory, 0);
  if (r == VK_SUCCESS && (props & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT))
    r = vkMapMemory(ctx.device(), b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped);
  if (r != VK_SUCCESS) {
    destroyBuffer(ctx.device(), b);
    return vkError("allocating " + std::to_string(size) + " bytes of buffer memory", r);
  }
  return b;
}

Result<Buffer> createHostBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
  return createBuffer(ctx, size, usage, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
}

Result<Buffer> createDeviceBuffer(Context& ctx, VkBufferUsageFlags usage, const void* data, VkDeviceSize size) {
  // A CPU device (lavapipe) or an integrated GPU: device memory the host can write, so no staging
  // copy and no queue submission, which would wait behind the frames still in the queue (a new
  // preview mesh uploaded in the UI thread waited for the previous frame's rendering).
  const VkPhysicalDeviceType type = ctx.deviceType();
  if (type == VK_PHYSICAL_DEVICE_TYPE_CPU || type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU) {
    Result<Buffer> direct = createBuffer(ctx, size, usage,
                                         VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                             VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (direct && direct->mapped) {
      std::memcpy(direct->mapped, data, size);
      return direct;
    }
    if (direct) destroyBuffer(ctx.device(), *direct);  // (not mapped: take the staging path)
  }
  Result<Buffer> staging = createHostBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  if (!staging) return Error{staging.error()};
  std::memcpy(staging->mapped, data, size);
  Result<Buffer> dst =
      createBuffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (!dst) {
    destroyBuffer(ctx.device(), *staging);
    return dst;
  }
  Status s = ctx.submitImmediate([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, size};
    vkCmdCopyBuffer(cmd, staging->buffer, dst->buffer, 1, &region);
  });
  destroyBuffer(ctx.device(), *staging);
  if (!s) {
    destroyBuffer(ctx.device(), *dst);
    return Error{"uploading a buffer: " + s.error()};
  }
  return dst;
}

void destroyBuffer(VkDevice device, Buffer& b) {
  if (b.mapped) vkUnmapMemory(device, b.memory);
  if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(device, b.memory, nullptr);
  b = Buffer{};
}

}  // namespace animorph::gpu
