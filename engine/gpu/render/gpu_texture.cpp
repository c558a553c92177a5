#include "gpu/render/gpu_texture.h"

#include "gpu/vulkan/vk_check.h"
#include "shared_constants.h"

namespace animorph::gpu {

namespace {

VkSamplerAddressMode addressMode(TextureWrap w) {
  switch (w) {
    case TextureWrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case TextureWrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case TextureWrap::Repeat: break;
  }
  return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

VkFilter filter(TextureFilter f) { return f == TextureFilter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }

}  // namespace

Result<VkDescriptorSetLayout> createMaterialSetLayout(VkDevice device) {
  VkDescriptorSetLayoutBinding b{AM_MATERIAL_BINDING_BASE_COLOR, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                 VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = 1;
  ci.pBindings = &b;
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  AM_VK_TRY(vkCreateDescriptorSetLayout(device, &ci, nullptr, &layout), "vkCreateDescriptorSetLayout");
  return layout;
}

Result<std::unique_ptr<GpuTexture>> GpuTexture::upload(Context& ctx, const TextureImage& texture) {
  const std::string what = "texture '" + texture.name + "'";
  if (!texture.valid()) return Error{what + ": no pixels"};
  const uint32_t maxSide = ctx.properties().limits.maxImageDimension2D;
  if (uint32_t(texture.width) > maxSide || uint32_t(texture.height) > maxSide)
    return Error{what + ": " + std::to_string(texture.width) + " x " + std::to_string(texture.height) +
                 " is larger than the device's largest image (" + std::to_string(maxSide) + ")"};
  std::unique_ptr<GpuTexture> t(new GpuTexture(ctx.device()));
  // The full chain of mipmaps (averaged in linear light on the CPU), so a minified texture is
  // filtered rather than aliased.
  const std::vector<TextureLevel> mips = textureMipLevels(texture);
  std::vector<ImageLevel> levels{{VkExtent2D{uint32_t(texture.width), uint32_t(texture.height)}, texture.rgba->data(),
                                  VkDeviceSize(texture.rgba->size())}};
  for (const TextureLevel& m : mips)
    levels.push_back({VkExtent2D{uint32_t(m.width), uint32_t(m.height)}, m.rgba.data(), VkDeviceSize(m.rgba.size())});
  Result<Image> img = createSampledImage(ctx, VK_FORMAT_R8G8B8A8_SRGB, levels);
  if (!img) return Error{what + ": " + img.error()};
  t->image_ = *img;

  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = filter(texture.magFilter);
  si.minFilter = filter(texture.minFilter);
  // Between levels as between texels: trilinear for a linear minification filter.
  si.mipmapMode = texture.minFilter == TextureFilter::Nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST
                                                              : VK_SAMPLER_MIPMAP_MODE_LINEAR;
  si.addressModeU = addressMode(texture.wrapS);
  si.addressModeV = addressMode(texture.wrapT);
  si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  si.maxLod = float(levels.size() - 1);
  AM_VK_TRY(vkCreateSampler(t->device_, &si, nullptr, &t->sampler_), "vkCreateSampler");
  Result<VkDescriptorSetLayout> layout = createMaterialSetLayout(t->device_);
  if (!layout) return Error{what + ": " + layout.error()};
  t->layout_ = *layout;
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  AM_VK_TRY(vkCreateDescriptorPool(t->device_, &pi, nullptr, &t->pool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = t->pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &t->layout_;
  AM_VK_TRY(vkAllocateDescriptorSets(t->device_, &ai, &t->set_), "vkAllocateDescriptorSets");
  VkDescriptorImageInfo ii{t->sampler_, t->image_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, t->set_, AM_MATERIAL_BINDING_BASE_COLOR, 0, 1,
                         VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &ii, nullptr, nullptr};
  vkUpdateDescriptorSets(t->device_, 1, &w, 0, nullptr);
  return t;
}

GpuTexture::~GpuTexture() {
  if (pool_) vkDestroyDescriptorPool(device_, pool_, nullptr);  // frees set_
  if (layout_) vkDestroyDescriptorSetLayout(device_, layout_, nullptr);
  if (sampler_) vkDestroySampler(device_, sampler_, nullptr);
  destroyImage(device_, image_);
}

}  // namespace animorph::gpu
