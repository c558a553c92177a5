#pragma once
// Turning VkResult codes into readable errors.
#include <string>

#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

// The enum name of a VkResult ("VK_ERROR_OUT_OF_DEVICE_MEMORY"), or "VkResult(N)".
const char* vkResultName(VkResult r);

// An Error "what: VK_ERROR_..." for a failed Vulkan call. VK_ERROR_DEVICE_LOST also raises
// deviceLost().
Error vkError(const std::string& what, VkResult r);

// Whether any Vulkan call reported VK_ERROR_DEVICE_LOST (through vkError) since the last
// clearDeviceLost(): the device and everything made with it are unusable; the editor recreates
// its whole Vulkan side. Any thread.
bool deviceLost();
void clearDeviceLost();

}  // namespace animorph::gpu

// Returns vkError(what, r) from the enclosing function (which returns Result<T> or Status)
// when the call fails.
#define AM_VK_TRY(call, what)                                            \
  do {                                                                   \
    VkResult am_vk_r_ = (call);                                          \
    if (am_vk_r_ != VK_SUCCESS) return ::animorph::gpu::vkError(what, am_vk_r_); \
  } while (0)
