#pragma once
// The editor viewport's kept image: the 3D scene rendered offscreen (colour + depth, the swapchain's
// colour format, a render pass compatible with the swapchain's), copied into every frame's image
// before the UI is drawn over it (Swapchain::beginPass with a FrameUnderlay). The scene is rendered
// again only when what it shows changed (scene_fingerprint.h); a frame where only the UI changed
// copies the kept image instead (docs/rendering.md, "Kept viewport image").
#include <functional>
#include <memory>

#include "gpu/present/swapchain.h"
#include "gpu/vulkan/context.h"
#include "gpu/vulkan/image.h"
#include "core/util/result.h"

namespace animorph::gpu {

class ViewportImage {
 public:
  // colorFormat: the swapchain's (pipelines made for its render pass draw here too). No images
  // until the first render. Errors: Vulkan failures.
  static Result<std::unique_ptr<ViewportImage>> create(Context& ctx, VkFormat colorFormat);
  ~ViewportImage();
  ViewportImage(const ViewportImage&) = delete;
  ViewportImage& operator=(const ViewportImage&) = delete;

  // Records into cmd (outside any render pass) the offscreen pass over a width x height image,
  // cleared, with draw recording the scene inside it (its rectangle: 0, 0, width, height); the image
  // then waits in TRANSFER_SRC_OPTIMAL for underlay() copies. A new size waits for the device to be
  // idle and remakes the images (the frames in flight may still copy the old ones). Errors: the
  // images or framebuffer could not be made (nothing recorded, valid() false).
  Status render(VkCommandBuffer cmd, uint32_t width, uint32_t height, const std::function<void(VkCommandBuffer)>& draw);
  // The kept image as a frame's underlay, copied to (x, y) of the frame; requires valid().
  FrameUnderlay underlay(int32_t x, int32_t y) const;
  // A render was recorded since the images were last made (or forgotten).
  bool valid() const { return valid_; }
  // The next frame must render the scene (a lost or remade device, a changed renderer).
  void invalidate() { valid_ = false; }
  VkExtent2D extent() const { return color_.extent; }

 private:
  explicit ViewportImage(Context& ctx) : ctx_(ctx) {}
  Status resize(uint32_t width, uint32_t height);
  void destroyImages();

  Context& ctx_;
  VkFormat colorFormat_ = VK_FORMAT_UNDEFINED;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  Image color_, depth_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  bool valid_ = false;
};

}  // namespace animorph::gpu
