#pragma once
// A TextureImage (rig/texture_image.h) uploaded once to device memory: an
// R8G8B8A8_SRGB image (sampling returns linear RGB) with its full mipmap chain
// (rig/texture_image.h textureMipLevels), a sampler with the texture's wrap modes
// and filters (trilinear when the minification filter is linear), and the descriptor set of the
// material pipelines' set AM_MATERIAL_SET that binds both.
#include <memory>

#include "gpu/vulkan/context.h"
#include "gpu/vulkan/image.h"
#include "core/rig/texture_image.h"

namespace animorph::gpu {

class GpuTexture {
 public:
  // Uploads texture (waits for the copy). Errors name the texture: not valid
  // (no pixels), larger than the device's maxImageDimension2D, Vulkan failures.
  static Result<std::unique_ptr<GpuTexture>> upload(Context& ctx, const TextureImage& texture);
  ~GpuTexture();
  GpuTexture(const GpuTexture&) = delete;
  GpuTexture& operator=(const GpuTexture&) = delete;

  // The set binding the image and its sampler (layout: createMaterialSetLayout).
  VkDescriptorSet set() const { return set_; }

 private:
  explicit GpuTexture(VkDevice device) : device_(device) {}
  VkDevice device_;
  Image image_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

// The layout of set AM_MATERIAL_SET (one combined image sampler, fragment stage):
// the renderer's pipeline layouts and every GpuTexture's set use identical ones.
Result<VkDescriptorSetLayout> createMaterialSetLayout(VkDevice device);

}  // namespace animorph::gpu
