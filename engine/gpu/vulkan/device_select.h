#pragma once
// Choosing a physical device: discrete > integrated > virtual > CPU (lavapipe),
// unless the user names one with ANIMORPH_GPU. Pure logic, testable without Vulkan.
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

struct DeviceCandidate {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  bool usable = true;  // Vulkan 1.1, a graphics queue (and present support when a surface is needed)
};

// Rank of a device type: higher is preferred (discrete 4, integrated 3, virtual 2, CPU 1, other 0).
int deviceTypeRank(VkPhysicalDeviceType type);

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other".
const char* deviceTypeName(VkPhysicalDeviceType type);

// Index of the device to use. overrideSpec (the ANIMORPH_GPU value, may be empty)
// is an index ("1") or a case-insensitive substring of the device name ("llvmpipe").
// Errors: no usable device, or an override that matches no usable device (the
// message lists the devices that exist). An override never silently falls back.
Result<size_t> pickPhysicalDevice(const std::vector<DeviceCandidate>& devices, const std::string& overrideSpec);

}  // namespace animorph::gpu
