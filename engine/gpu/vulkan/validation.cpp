#include "gpu/vulkan/validation.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace animorph::gpu {

bool validationRequested() {
  const char* env = std::getenv("ANIMORPH_VALIDATION");
  if (env && *env) return std::strcmp(env, "0") != 0;
#ifdef NDEBUG
  return false;
#else
  return true;
#endif
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT types,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* counters = static_cast<ValidationCounters*>(user);
  const bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  const bool validation = types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  const bool performance = types & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  if (error && validation) counters->errors.fetch_add(1);
  else if (!error && (validation || performance)) counters->warnings.fetch_add(1);
  if (counters->print)
    std::fprintf(stderr, "[vulkan %s] %s\n", error ? "error" : "warning",
                 data && data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;  // never abort the call that triggered the message
}

}  // namespace

VkDebugUtilsMessengerCreateInfoEXT debugMessengerInfo(ValidationCounters* counters) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = onDebugMessage;
  info.pUserData = counters;
  return info;
}

}  // namespace animorph::gpu
