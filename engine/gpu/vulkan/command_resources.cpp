#include "gpu/vulkan/command_resources.h"

#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

Status createCommandResources(VkDevice dev, uint32_t queueFamily, uint32_t count, VkCommandPool* pool,
                              VkCommandBuffer* cmds, VkFence* fences, bool signalled) {
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = queueFamily;
  AM_VK_TRY(vkCreateCommandPool(dev, &pci, nullptr, pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cai.commandPool = *pool;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = count;
  AM_VK_TRY(vkAllocateCommandBuffers(dev, &cai, cmds), "vkAllocateCommandBuffers");
  if (!fences) return Status::success();
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (signalled) fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  for (uint32_t i = 0; i < count; ++i) AM_VK_TRY(vkCreateFence(dev, &fci, nullptr, &fences[i]), "vkCreateFence");
  return Status::success();
}

}  // namespace animorph::gpu
