#include "gpu/vulkan/shader_module.h"

#include <string>

#include "gpu/vulkan/shader_blobs.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

Result<VkShaderModule> createShaderModule(VkDevice device, const char* name) {
  std::span<const uint32_t> code = shaderBlob(name);
  if (code.empty()) return Error{std::string("shader ") + name + " is not embedded in this build (shaders/" + name + ".glsl)"};
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = code.size_bytes();
  ci.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  AM_VK_TRY(vkCreateShaderModule(device, &ci, nullptr, &module), std::string("vkCreateShaderModule ") + name);
  return module;
}

}  // namespace animorph::gpu
