#pragma once
// The Vulkan context: instance (+ debug messenger), the chosen physical device,
// one logical device with one graphics queue, and (windowed mode) the surface.
// Headless mode draws only into offscreen targets (CLI, tests); windowed mode
// also presents to a GLFW window (swapchain.h). Single-threaded: every call on
// a Context and the objects made from it happens on one thread.
#include <functional>
#include <memory>
#include <string>

#include <vulkan/vulkan.h>

#include "core/util/result.h"
#include "gpu/vulkan/validation.h"

struct GLFWwindow;

namespace animorph::gpu {

struct ContextSettings {
  // Window to present to (glfwInit done, created with GLFW_NO_API); null: headless.
  GLFWwindow* window = nullptr;
  // Enable VK_LAYER_KHRONOS_validation (see validationRequested()). When the
  // layer is not installed the context still comes up, without it.
  bool validation = validationRequested();
  // Device choice: index or name substring; default: the ANIMORPH_GPU variable.
  // Empty: discrete > integrated > virtual > CPU.
  std::string deviceOverride = defaultDeviceOverride();
  // Print validation messages to stderr.
  bool printValidationMessages = true;

  static std::string defaultDeviceOverride();  // getenv("ANIMORPH_GPU") or ""
};

class Context {
 public:
  // Creates the context. Errors (no Vulkan loader or driver, no usable device,
  // an ANIMORPH_GPU override that matches nothing, surface failure) come back as a
  // message; nothing is left allocated and the caller can carry on without a GPU.
  static Result<std::unique_ptr<Context>> create(const ContextSettings& settings);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }               // graphics (+ present) queue
  uint32_t queueFamily() const { return queueFamily_; }
  VkSurfaceKHR surface() const { return surface_; }      // VK_NULL_HANDLE when headless
  GLFWwindow* window() const { return window_; }
  bool headless() const { return surface_ == VK_NULL_HANDLE; }

  // "llvmpipe (LLVM 15.0.6, 256 bits)", for the status bar.
  const std::string& deviceName() const { return deviceName_; }
  VkPhysicalDeviceType deviceType() const { return properties_.deviceType; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  // The depth format used by every render pass (D32 preferred).
  VkFormat depthFormat() const { return depthFormat_; }
  // fillModeNonSolid is enabled (wireframe by polygon mode rather than edge lists).
  bool supportsWireframeFill() const { return fillModeNonSolid_; }
  // VK_EXT_external_memory_host is enabled (windowed contexts): host memory such as an X11
  // shared-memory segment can back a buffer (the swapchain's host presentation).
  bool supportsHostMemoryImport() const { return hostMemoryImport_; }
  VkDeviceSize hostPointerAlignment() const { return hostPointerAlignment_; }

  bool validationEnabled() const { return validationEnabled_; }
  uint32_t validationErrorCount() const { return counters_->errors.load(); }

  // A descriptor pool for Dear ImGui's Vulkan backend (COMBINED_IMAGE_SAMPLER,
  // FREE_DESCRIPTOR_SET bit), owned by the context.
  VkDescriptorPool uiDescriptorPool() const { return uiDescriptorPool_; }

  // Memory type index with typeBits and props, or UINT32_MAX when there is none.
  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags props) const;

  // Records commands with record(cmd), submits them and waits (uploads, font
  // texture creation). Not for per-frame work. Errors: Vulkan failures.
  Status submitImmediate(const std::function<void(VkCommandBuffer)>& record);

  // vkDeviceWaitIdle; call before destroying objects that may be in flight.
  void waitIdle() const;

 private:
  Context() = default;
  Status init(const ContextSettings& settings);
  // init's steps, in order: the instance (validation layer and debug messenger when asked and
  // installed), the physical device (pickPhysicalDevice over the usable ones), the logical device
  // and its queue, the depth format. Each returns what failed.
  Status createInstance(bool validation);
  Status choosePhysicalDevice(const std::string& deviceOverride);
  Status createDevice();
  Status chooseDepthFormat();

  std::unique_ptr<ValidationCounters> counters_ = std::make_unique<ValidationCounters>();
  GLFWwindow* window_ = nullptr;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool immediatePool_ = VK_NULL_HANDLE;
  VkCommandBuffer immediateCmd_ = VK_NULL_HANDLE;
  VkFence immediateFence_ = VK_NULL_HANDLE;
  VkDescriptorPool uiDescriptorPool_ = VK_NULL_HANDLE;
  VkFormat depthFormat_ = VK_FORMAT_UNDEFINED;
  std::string deviceName_;
  bool fillModeNonSolid_ = false;
  bool hostMemoryImport_ = false;
  VkDeviceSize hostPointerAlignment_ = 4096;
  bool validationEnabled_ = false;
};

}  // namespace animorph::gpu
