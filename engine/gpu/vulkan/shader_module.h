#pragma once
// Shader modules from the embedded SPIR-V (shader_blobs.h).
#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

// A module for embedded shader `name` ("mesh.vert"). Errors: unknown name
// (the shader was not built), Vulkan failure.
Result<VkShaderModule> createShaderModule(VkDevice device, const char* name);

}  // namespace animorph::gpu
