#include "gpu/vulkan/context.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "gpu/vulkan/command_resources.h"
#include "gpu/vulkan/device_select.h"
#include "gpu/vulkan/driver_pin.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

std::string ContextSettings::defaultDeviceOverride() {
  const char* env = std::getenv("ANIMORPH_GPU");
  return env ? std::string(env) : std::string();
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasLayer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

bool hasInstanceExtension(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
  for (const auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
  for (const auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// Graphics queue family (with present support for surface), or -1.
int findQueueFamily(VkPhysicalDevice pd, VkSurfaceKHR surface) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
  for (uint32_t i = 0; i < n; ++i) {
    if (!(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
    if (surface != VK_NULL_HANDLE) {
      VkBool32 present = VK_FALSE;
      vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present);
      if (!present) continue;
    }
    return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

Result<std::unique_ptr<Context>> Context::create(const ContextSettings& settings) {
  std::unique_ptr<Context> ctx(new Context());
  Status s = ctx->init(settings);
  if (!s) return Error{"Vulkan: " + s.error()};  // ~Context releases whatever init made
  return ctx;
}

Status Context::init(const ContextSettings& settings) {
  window_ = settings.window;
  counters_->print = settings.printValidationMessages;
  if (Status s = createInstance(settings.validation); !s) return s;
  if (window_) AM_VK_TRY(glfwCreateWindowSurface(instance_, window_, nullptr, &surface_), "glfwCreateWindowSurface");
  if (Status s = choosePhysicalDevice(settings.deviceOverride); !s) return s;
  if (Status s = createDevice(); !s) return s;
  if (Status s = chooseDepthFormat(); !s) return s;
  if (Status c = createCommandResources(device_, queueFamily_, 1, &immediatePool_, &immediateCmd_, &immediateFence_); !c)
    return Error{c.error()};

  VkDescriptorPoolSize uiSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 64};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  dpi.maxSets = 64;
  dpi.poolSizeCount = 1;
  dpi.pPoolSizes = &uiSize;
  AM_VK_TRY(vkCreateDescriptorPool(device_, &dpi, nullptr, &uiDescriptorPool_), "vkCreateDescriptorPool (UI)");
  return Status::success();
}

Status Context::createInstance(bool validation) {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  if (validation) {
    if (hasLayer(kValidationLayer)) {
      layers.push_back(kValidationLayer);
      validationEnabled_ = true;
    } else {
      std::fprintf(stderr,
                   "animorph: validation requested but %s is not installed (apt-get install "
                   "vulkan-validationlayers); continuing without it\n",
                   kValidationLayer);
    }
  }
  const bool debugUtils = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (window_) {
    if (!glfwVulkanSupported()) return Error{"GLFW finds no Vulkan loader or driver for windows"};
    uint32_t n = 0;
    const char** glfwExts = glfwGetRequiredInstanceExtensions(&n);
    if (!glfwExts) return Error{"GLFW cannot present with Vulkan on this display (no surface extensions)"};
    for (uint32_t i = 0; i < n; ++i) extensions.push_back(glfwExts[i]);
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "Animorph";
  app.applicationVersion = VK_MAKE_VERSION(0, 1, 0);
  app.pEngineName = "Animorph";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  ici.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo = debugMessengerInfo(counters_.get());
  if (debugUtils && validationEnabled_) ici.pNext = &messengerInfo;  // also covers instance creation
  VkResult r = vkCreateInstance(&ici, nullptr, &instance_);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
    return Error{std::string("no Vulkan driver found (") + vkResultName(r) +
                 "); install mesa-vulkan-drivers for the CPU renderer, or a GPU driver"};
  AM_VK_TRY(r, "vkCreateInstance");

  if (debugUtils && validationEnabled_) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) AM_VK_TRY(create(instance_, &messengerInfo, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
  return Status::success();
}

Status Context::choosePhysicalDevice(const std::string& deviceOverride) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> physicals(count);
  vkEnumeratePhysicalDevices(instance_, &count, physicals.data());
  keepVulkanDriversLoadedUnderSanitizer();  // a no-op outside AddressSanitizer builds
  std::vector<DeviceCandidate> candidates;
  for (VkPhysicalDevice pd : physicals) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    DeviceCandidate c;
    c.name = p.deviceName;
    c.type = p.deviceType;
    c.usable = p.apiVersion >= VK_API_VERSION_1_1 && findQueueFamily(pd, surface_) >= 0 &&
               (!window_ || hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME));
    candidates.push_back(c);
  }
  Result<size_t> picked = pickPhysicalDevice(candidates, deviceOverride);
  if (!picked) return Error{picked.error()};
  physical_ = physicals[*picked];
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  deviceName_ = properties_.deviceName;
  queueFamily_ = static_cast<uint32_t>(findQueueFamily(physical_, surface_));
  return Status::success();
}

Status Context::createDevice() {
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical_, &supported);
  VkPhysicalDeviceFeatures enabled{};
  enabled.fillModeNonSolid = supported.fillModeNonSolid;
  fillModeNonSolid_ = supported.fillModeNonSolid == VK_TRUE;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  std::vector<const char*> deviceExts;
  if (window_) deviceExts.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  if (window_ && hasDeviceExtension(physical_, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME)) {
    deviceExts.push_back(VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);
    hostMemoryImport_ = true;
    VkPhysicalDeviceExternalMemoryHostPropertiesEXT hp{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &hp;
    vkGetPhysicalDeviceProperties2(physical_, &p2);
    hostPointerAlignment_ = std::max<VkDeviceSize>(hp.minImportedHostPointerAlignment, 1);
  }
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = static_cast<uint32_t>(deviceExts.size());
  dci.ppEnabledExtensionNames = deviceExts.data();
  dci.pEnabledFeatures = &enabled;
  AM_VK_TRY(vkCreateDevice(physical_, &dci, nullptr, &device_), "vkCreateDevice (" + deviceName_ + ")");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  return Status::success();
}

Status Context::chooseDepthFormat() {
  depthFormat_ = VK_FORMAT_UNDEFINED;
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D24_UNORM_S8_UINT,
                     VK_FORMAT_D16_UNORM}) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(physical_, f, &fp);
    if (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
      depthFormat_ = f;
      return Status::success();
    }
  }
  return Error{deviceName_ + " supports no depth attachment format"};
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (uiDescriptorPool_) vkDestroyDescriptorPool(device_, uiDescriptorPool_, nullptr);
    if (immediateFence_) vkDestroyFence(device_, immediateFence_, nullptr);
    if (immediatePool_) vkDestroyCommandPool(device_, immediatePool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (instance_) {
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    if (messenger_) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroy) destroy(instance_, messenger_, nullptr);
    }
    vkDestroyInstance(instance_, nullptr);
  }
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags props) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & props) == props) return i;
  return UINT32_MAX;
}

Status Context::submitImmediate(const std::function<void(VkCommandBuffer)>& record) {
  AM_VK_TRY(vkResetCommandBuffer(immediateCmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  AM_VK_TRY(vkBeginCommandBuffer(immediateCmd_, &bi), "vkBeginCommandBuffer");
  record(immediateCmd_);
  AM_VK_TRY(vkEndCommandBuffer(immediateCmd_), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &immediateCmd_;
  AM_VK_TRY(vkResetFences(device_, 1, &immediateFence_), "vkResetFences");
  AM_VK_TRY(vkQueueSubmit(queue_, 1, &si, immediateFence_), "vkQueueSubmit");
  AM_VK_TRY(vkWaitForFences(device_, 1, &immediateFence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  return Status::success();
}

void Context::waitIdle() const {
  if (device_) vkDeviceWaitIdle(device_);
}

}  // namespace animorph::gpu
