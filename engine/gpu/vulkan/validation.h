#pragma once
// Vulkan validation: when it is on, and a debug messenger that prints and counts
// what the layers report.
#include <atomic>
#include <cstdint>

#include <vulkan/vulkan.h>

namespace animorph::gpu {

// Counts of messages reported through a debug messenger.
struct ValidationCounters {
  std::atomic<uint32_t> errors{0};    // validation-layer errors (VALIDATION type, ERROR severity)
  std::atomic<uint32_t> warnings{0};  // validation/performance warnings
  bool print = true;                  // echo every error and warning to stderr
};

// True when validation layers should be enabled: env ANIMORPH_VALIDATION=1, or a
// Debug build (NDEBUG undefined) unless ANIMORPH_VALIDATION=0.
bool validationRequested();

// A messenger description reporting warnings and errors into counters (which
// must outlive the messenger); usable for vkCreateDebugUtilsMessengerEXT and,
// chained into VkInstanceCreateInfo::pNext, for instance creation itself.
VkDebugUtilsMessengerCreateInfoEXT debugMessengerInfo(ValidationCounters* counters);

}  // namespace animorph::gpu
