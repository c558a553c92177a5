#pragma once
// An offscreen colour (RGBA8) + depth target with its render pass, rendered
// synchronously and read back to host memory (CLI renders, tests, thumbnails).
// Each render() waits for the GPU, so any SceneRenderer ring slot is free.
#include <functional>
#include <memory>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "gpu/vulkan/image.h"
#include "gpu/present/rgba_image.h"

namespace animorph::gpu {

class OffscreenTarget {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;

  // A width x height target. Errors: zero or too large a size, Vulkan failures.
  static Result<std::unique_ptr<OffscreenTarget>> create(Context& ctx, uint32_t width, uint32_t height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  // Recreates the images for a new size; the render pass (and so the pipelines
  // made for it) stay valid. Errors: as create; on error the old size remains.
  Status resize(uint32_t width, uint32_t height);

  VkRenderPass renderPass() const { return renderPass_; }
  VkExtent2D extent() const { return color_.extent; }

  // Begins the render pass (colour cleared to clearColor, depth to 1), calls
  // record(cmd) inside it, copies the colour image to host memory when
  // readBack, submits and waits. Errors: Vulkan failures.
  Status render(const std::function<void(VkCommandBuffer)>& record, const glm::vec4& clearColor = {0, 0, 0, 1},
                bool readBack = true);

  // Number of the render() in progress (or the last one): the frame serial to
  // pass to SceneRenderer::record from inside the record callback.
  uint64_t serial() const { return serial_; }

  // The colour image of the last render() with readBack (empty before).
  const RgbaImage& image() const { return image_; }

 private:
  explicit OffscreenTarget(Context& ctx) : ctx_(ctx) {}
  Status createImages(uint32_t width, uint32_t height);
  void destroyImages();

  Context& ctx_;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  Image color_, depth_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  Buffer readback_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  RgbaImage image_;
  uint64_t serial_ = 0;
};

}  // namespace animorph::gpu
