#pragma once
// The command-recording set-up every GPU user repeats: a command pool on one queue family whose
// buffers can be reset one by one, count primary command buffers from it, and count fences
// (signalled at creation when signalled is true: a frame loop's first wait returns at once).
// The caller owns and destroys what it gets (vkDestroyFence, vkDestroyCommandPool).
#include <cstdint>

#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

// Fills *pool, cmds[0..count) and, when fences is not null, fences[0..count). On an error the
// handles made so far are left in the outputs for the caller's destructor to release.
Status createCommandResources(VkDevice dev, uint32_t queueFamily, uint32_t count, VkCommandPool* pool,
                              VkCommandBuffer* cmds, VkFence* fences, bool signalled = false);

}  // namespace animorph::gpu
