#include "gpu/vulkan/device_select.h"

#include <algorithm>
#include <cctype>

namespace animorph::gpu {

int deviceTypeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string listDevices(const std::vector<DeviceCandidate>& devices) {
  if (devices.empty()) return "none";
  std::string out;
  for (size_t i = 0; i < devices.size(); ++i) {
    if (i) out += "; ";
    out += std::to_string(i) + ": " + devices[i].name + " (" + deviceTypeName(devices[i].type) +
           (devices[i].usable ? "" : ", unusable: no graphics/present queue") + ")";
  }
  return out;
}

bool isIndex(const std::string& s) {
  return !s.empty() && s.size() < 6 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

Result<size_t> pickPhysicalDevice(const std::vector<DeviceCandidate>& devices, const std::string& overrideSpec) {
  if (!overrideSpec.empty()) {
    if (isIndex(overrideSpec)) {
      size_t i = std::stoul(overrideSpec);
      if (i < devices.size() && devices[i].usable) return i;
      return Error{"ANIMORPH_GPU=" + overrideSpec + ": no usable Vulkan device with that index; devices: " +
                   listDevices(devices)};
    }
    const std::string needle = lower(overrideSpec);
    for (size_t i = 0; i < devices.size(); ++i)
      if (devices[i].usable && lower(devices[i].name).find(needle) != std::string::npos) return i;
    return Error{"ANIMORPH_GPU=" + overrideSpec + ": matches no usable Vulkan device; devices: " +
                 listDevices(devices) + ". Unset ANIMORPH_GPU to pick automatically."};
  }
  size_t best = devices.size();
  for (size_t i = 0; i < devices.size(); ++i) {
    if (!devices[i].usable) continue;
    if (best == devices.size() || deviceTypeRank(devices[i].type) > deviceTypeRank(devices[best].type)) best = i;
  }
  if (best == devices.size())
    return Error{"no usable Vulkan device (one with a graphics queue, and present support when drawing to a window); "
                 "devices: " + listDevices(devices) +
                 ". On a machine without a GPU install mesa-vulkan-drivers (lavapipe)."};
  return best;
}

}  // namespace animorph::gpu
