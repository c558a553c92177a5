#pragma once
// Vulkan buffers with their own memory (plain struct + free functions).
#include <vulkan/vulkan.h>

#include "gpu/vulkan/context.h"

namespace animorph::gpu {

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // persistent mapping of host-visible buffers, else null
};

// A buffer of size bytes with memory of props; host-visible buffers are mapped
// persistently. Errors: no memory type with props, allocation failure.
Result<Buffer> createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags props);

// A host-visible, host-coherent, mapped buffer (per-frame data, readback).
Result<Buffer> createHostBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage);

// A device-local buffer filled with size bytes of data: on a CPU device or an integrated GPU with
// host-visible device memory written directly (no submission, no wait), else through a staging
// buffer (usage gets TRANSFER_DST added; waits for the copy, and so for the work queued before it).
// Errors: as createBuffer.
Result<Buffer> createDeviceBuffer(Context& ctx, VkBufferUsageFlags usage, const void* data, VkDeviceSize size);

// Frees buffer (no-op on an empty one) and resets it to empty.
void destroyBuffer(VkDevice device, Buffer& buffer);

}  // namespace animorph::gpu
