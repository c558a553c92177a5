#include "gpu/present/viewport_image.h"

#include "gpu/vulkan/render_pass.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

Result<std::unique_ptr<ViewportImage>> ViewportImage::create(Context& ctx, VkFormat colorFormat) {
  std::unique_ptr<ViewportImage> v(new ViewportImage(ctx));
  v->colorFormat_ = colorFormat;
  Result<VkRenderPass> pass =
      createSceneRenderPass(ctx.device(), colorFormat, ctx.depthFormat(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  if (!pass) return Error{"viewport image: " + pass.error()};
  v->renderPass_ = *pass;
  return v;
}

ViewportImage::~ViewportImage() {
  destroyImages();
  if (renderPass_) vkDestroyRenderPass(ctx_.device(), renderPass_, nullptr);
}

void ViewportImage::destroyImages() {
  VkDevice dev = ctx_.device();
  if (framebuffer_) vkDestroyFramebuffer(dev, framebuffer_, nullptr);
  framebuffer_ = VK_NULL_HANDLE;
  destroyImage(dev, color_);
  destroyImage(dev, depth_);
  valid_ = false;
}

Status ViewportImage::resize(uint32_t width, uint32_t height) {
  if (color_.image) ctx_.waitIdle();  // earlier frames may still copy or draw the old images
  destroyImages();
  const VkExtent2D extent{width, height};
  Result<Image> color = createImage(ctx_, extent, colorFormat_,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                    VK_IMAGE_ASPECT_COLOR_BIT);
  if (!color) return Error{"viewport image: " + color.error()};
  color_ = *color;
  Result<Image> depth =
      createImage(ctx_, extent, ctx_.depthFormat(), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  if (!depth) {
    destroyImages();
    return Error{"viewport image: " + depth.error()};
  }
  depth_ = *depth;
  Result<VkFramebuffer> fb = createSceneFramebuffer(ctx_.device(), renderPass_, color_.view, depth_.view, extent);
  if (!fb) {
    destroyImages();
    return Error{"viewport image: " + fb.error()};
  }
  framebuffer_ = *fb;
  return Status::success();
}

Status ViewportImage::render(VkCommandBuffer cmd, uint32_t width, uint32_t height,
                             const std::function<void(VkCommandBuffer)>& draw) {
  if (!framebuffer_ || color_.extent.width != width || color_.extent.height != height)
    if (Status s = resize(width, height); !s) return s;
  const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // SceneRenderer::record clears its rectangle itself
  beginScenePass(cmd, renderPass_, framebuffer_, color_.extent, black);
  draw(cmd);
  vkCmdEndRenderPass(cmd);
  valid_ = true;
  return Status::success();
}

FrameUnderlay ViewportImage::underlay(int32_t x, int32_t y) const {
  FrameUnderlay u;
  u.image = color_.image;
  u.rect = {{x, y}, color_.extent};
  return u;
}

}  // namespace animorph::gpu
