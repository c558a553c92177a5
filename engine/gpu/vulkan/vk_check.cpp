#include "gpu/vulkan/vk_check.h"

#include <atomic>

namespace animorph::gpu {

const char* vkResultName(VkResult r) {
  switch (r) {
#define AM_CASE(x) \
  case x:          \
    return #x;
    AM_CASE(VK_SUCCESS)
    AM_CASE(VK_NOT_READY)
    AM_CASE(VK_TIMEOUT)
    AM_CASE(VK_EVENT_SET)
    AM_CASE(VK_EVENT_RESET)
    AM_CASE(VK_INCOMPLETE)
    AM_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    AM_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    AM_CASE(VK_ERROR_INITIALIZATION_FAILED)
    AM_CASE(VK_ERROR_DEVICE_LOST)
    AM_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    AM_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    AM_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    AM_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    AM_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    AM_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    AM_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    AM_CASE(VK_ERROR_FRAGMENTED_POOL)
    AM_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    AM_CASE(VK_ERROR_SURFACE_LOST_KHR)
    AM_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    AM_CASE(VK_SUBOPTIMAL_KHR)
    AM_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    AM_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef AM_CASE
    default:
      return "VkResult(unknown)";
  }
}

namespace {
std::atomic<bool> gDeviceLost{false};
}  // namespace

Error vkError(const std::string& what, VkResult r) {
  if (r == VK_ERROR_DEVICE_LOST) gDeviceLost.store(true);
  return Error{what + ": " + vkResultName(r)};
}

bool deviceLost() { return gDeviceLost.load(); }
void clearDeviceLost() { gDeviceLost.store(false); }

}  // namespace animorph::gpu
