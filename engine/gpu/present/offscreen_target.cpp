#include "gpu/present/offscreen_target.h"

#include <cstring>

#include "gpu/vulkan/command_resources.h"
#include "gpu/vulkan/render_pass.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

Result<std::unique_ptr<OffscreenTarget>> OffscreenTarget::create(Context& ctx, uint32_t width, uint32_t height) {
  std::unique_ptr<OffscreenTarget> t(new OffscreenTarget(ctx));
  VkDevice dev = ctx.device();
  Result<VkRenderPass> pass =
      createSceneRenderPass(dev, kColorFormat, ctx.depthFormat(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  if (!pass) return Error{"offscreen target: " + pass.error()};
  t->renderPass_ = *pass;
  if (Status c = createCommandResources(dev, ctx.queueFamily(), 1, &t->pool_, &t->cmd_, &t->fence_); !c)
    return Error{"offscreen target: " + c.error()};
  Status s = t->createImages(width, height);
  if (!s) return Error{"offscreen target: " + s.error()};
  return t;
}

OffscreenTarget::~OffscreenTarget() {
  VkDevice dev = ctx_.device();
  vkDeviceWaitIdle(dev);
  destroyImages();
  if (fence_) vkDestroyFence(dev, fence_, nullptr);
  if (pool_) vkDestroyCommandPool(dev, pool_, nullptr);
  if (renderPass_) vkDestroyRenderPass(dev, renderPass_, nullptr);
}

Status OffscreenTarget::createImages(uint32_t width, uint32_t height) {
  const uint32_t maxDim = ctx_.properties().limits.maxFramebufferWidth;
  if (width == 0 || height == 0 || width > maxDim || height > ctx_.properties().limits.maxFramebufferHeight)
    return Error{"size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
                 std::to_string(maxDim)};
  VkExtent2D extent{width, height};
  Result<Image> color = createImage(ctx_, extent, kColorFormat,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                    VK_IMAGE_ASPECT_COLOR_BIT);
  if (!color) return Error{color.error()};
  Result<Image> depth =
      createImage(ctx_, extent, ctx_.depthFormat(), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  if (!depth) {
    destroyImage(ctx_.device(), *color);
    return Error{depth.error()};
  }
  Result<Buffer> readback = createHostBuffer(ctx_, VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  if (!readback) {
    destroyImage(ctx_.device(), *color);
    destroyImage(ctx_.device(), *depth);
    return Error{readback.error()};
  }
  Result<VkFramebuffer> fb = createSceneFramebuffer(ctx_.device(), renderPass_, color->view, depth->view, extent);
  if (!fb) {
    destroyImage(ctx_.device(), *color);
    destroyImage(ctx_.device(), *depth);
    destroyBuffer(ctx_.device(), *readback);
    return Error{fb.error()};
  }
  destroyImages();
  color_ = *color;
  depth_ = *depth;
  readback_ = *readback;
  framebuffer_ = *fb;
  image_ = RgbaImage{};
  return Status::success();
}

void OffscreenTarget::destroyImages() {
  VkDevice dev = ctx_.device();
  if (framebuffer_) vkDestroyFramebuffer(dev, framebuffer_, nullptr);
  framebuffer_ = VK_NULL_HANDLE;
  destroyImage(dev, color_);
  destroyImage(dev, depth_);
  destroyBuffer(dev, readback_);
}

Status OffscreenTarget::resize(uint32_t width, uint32_t height) {
  if (width == color_.extent.width && height == color_.extent.height) return Status::success();
  vkDeviceWaitIdle(ctx_.device());
  return createImages(width, height);
}

Status OffscreenTarget::render(const std::function<void(VkCommandBuffer)>& record, const glm::vec4& clearColor,
                               bool readBack) {
  VkDevice dev = ctx_.device();
  ++serial_;
  AM_VK_TRY(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  AM_VK_TRY(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
  const float clear[4] = {clearColor.r, clearColor.g, clearColor.b, clearColor.a};
  beginScenePass(cmd_, renderPass_, framebuffer_, color_.extent, clear);
  record(cmd_);
  vkCmdEndRenderPass(cmd_);
  if (readBack) {
    // The render pass leaves colour in TRANSFER_SRC_OPTIMAL, visible to transfers.
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {color_.extent.width, color_.extent.height, 1};
    vkCmdCopyImageToBuffer(cmd_, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer, 1, &region);
    VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.buffer = readback_.buffer;
    toHost.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &toHost, 0,
                         nullptr);
  }
  AM_VK_TRY(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  AM_VK_TRY(vkResetFences(dev, 1, &fence_), "vkResetFences");
  AM_VK_TRY(vkQueueSubmit(ctx_.queue(), 1, &si, fence_), "vkQueueSubmit (offscreen)");
  AM_VK_TRY(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences (offscreen)");
  if (readBack) {
    image_.width = color_.extent.width;
    image_.height = color_.extent.height;
    image_.pixels.resize(size_t(image_.width) * image_.height * 4);
    std::memcpy(image_.pixels.data(), readback_.mapped, image_.pixels.size());
  }
  return Status::success();
}

}  // namespace animorph::gpu
