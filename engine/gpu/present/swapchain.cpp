#include "gpu/present/swapchain.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include <unistd.h>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "gpu/vulkan/command_resources.h"
#include "gpu/vulkan/render_pass.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

namespace {

VkExtent2D framebufferSize(GLFWwindow* window) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window, &w, &h);
  return {static_cast<uint32_t>(std::max(w, 0)), static_cast<uint32_t>(std::max(h, 0))};
}

VkPresentModeKHR toVk(PresentMode m) {
  switch (m) {
    case PresentMode::Mailbox: return VK_PRESENT_MODE_MAILBOX_KHR;
    case PresentMode::Immediate: return VK_PRESENT_MODE_IMMEDIATE_KHR;
    default: return VK_PRESENT_MODE_FIFO_KHR;
  }
}

bool isBgra(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_B8G8R8A8_SRGB; }

// A transfer-destination buffer whose memory is `bytes` of host memory at `ptr` (an X11 shared
// segment), through VK_EXT_external_memory_host: the device's copy writes the window's pixels
// straight into the segment. The Buffer is not mapped (its `mapped` stays null).
Result<Buffer> importHostBuffer(const Context& ctx, void* ptr, VkDeviceSize bytes) {
  VkDevice dev = ctx.device();
  auto hostPointerProperties = reinterpret_cast<PFN_vkGetMemoryHostPointerPropertiesEXT>(
      vkGetDeviceProcAddr(dev, "vkGetMemoryHostPointerPropertiesEXT"));
  if (!hostPointerProperties) return Error{"vkGetMemoryHostPointerPropertiesEXT is missing"};
  VkExternalMemoryBufferCreateInfo ext{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
  ext.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.pNext = &ext;
  bi.size = bytes;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  Buffer b;
  AM_VK_TRY(vkCreateBuffer(dev, &bi, nullptr, &b.buffer), "vkCreateBuffer (imported host memory)");
  VkMemoryHostPointerPropertiesEXT hp{VK_STRUCTURE_TYPE_MEMORY_HOST_POINTER_PROPERTIES_EXT};
  VkResult r = hostPointerProperties(dev, VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT, ptr, &hp);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(dev, b.buffer, &req);
  const uint32_t bits = req.memoryTypeBits & hp.memoryTypeBits;
  uint32_t type = r == VK_SUCCESS && bits ? ctx.findMemoryType(bits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) : UINT32_MAX;
  if (type == UINT32_MAX) {
    destroyBuffer(dev, b);
    return Error{"the shared segment cannot back a buffer"};
  }
  VkImportMemoryHostPointerInfoEXT imp{VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT};
  imp.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
  imp.pHostPointer = ptr;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.pNext = &imp;
  ai.allocationSize = bytes;
  ai.memoryTypeIndex = type;
  r = vkAllocateMemory(dev, &ai, nullptr, &b.memory);
  if (r == VK_SUCCESS) r = vkBindBufferMemory(dev, b.buffer, b.memory, 0);
  if (r != VK_SUCCESS) {
    destroyBuffer(dev, b);
    return vkError("importing the shared segment", r);
  }
  b.size = bytes;
  return b;
}

}  // namespace

Result<std::unique_ptr<Swapchain>> Swapchain::create(Context& ctx, const SwapchainSettings& settings) {
  if (ctx.headless()) return Error{"swapchain: the Vulkan context was created without a window"};
  std::unique_ptr<Swapchain> s(new Swapchain(ctx));
  Status st = s->init(settings);
  if (!st) return Error{"swapchain: " + st.error()};
  return s;
}

Status Swapchain::init(const SwapchainSettings& settings) {
  settings_ = settings;
  VkDevice dev = ctx_.device();
  VkPhysicalDevice pd = ctx_.physicalDevice();
  uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, ctx_.surface(), &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, ctx_.surface(), &n, formats.data());
  if (formats.empty()) return Error{"the window surface reports no formats"};
  // UNORM: the shaders and Dear ImGui write display-ready (gamma-encoded) colours.
  format_ = formats[0];
  for (const auto& f : formats)
    if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
        f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
      format_ = f;
      break;
    }
  presentPath_ = "Vulkan WSI";
  if (settings.hostPresent && ctx_.deviceType() == VK_PHYSICAL_DEVICE_TYPE_CPU) {
    const char* env = std::getenv("ANIMORPH_PRESENT");
    std::string why = "ANIMORPH_PRESENT=wsi";
    if (!env || std::string(env) != "wsi") host_ = X11ShmPresenter::create(ctx_.window(), why);
    if (host_) {
      format_ = {VK_FORMAT_B8G8R8A8_UNORM, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};  // the window's BGRX bytes
      presentPath_ = "MIT-SHM (host)";
    } else {
      presentPath_ += " (no MIT-SHM: " + why + ")";
    }
  }
  Result<VkRenderPass> pass = createSceneRenderPass(
      dev, format_.format, ctx_.depthFormat(), host_ ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  if (!pass) return Error{pass.error()};
  renderPass_ = *pass;
  Result<VkRenderPass> loadPass =
      createSceneRenderPass(dev, format_.format, ctx_.depthFormat(),
                            host_ ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, true);
  if (!loadPass) return Error{loadPass.error()};
  loadPass_ = *loadPass;

  if (Status c = createCommandResources(dev, ctx_.queueFamily(), kFramesInFlight, &pool_, cmds_, inFlight_,
                                        /*signalled=*/true);
      !c)
    return c;
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    AM_VK_TRY(vkCreateSemaphore(dev, &sci, nullptr, &acquired_[i]), "vkCreateSemaphore");
  }
  VkExtent2D size = framebufferSize(ctx_.window());
  if (size.width == 0 || size.height == 0) {
    needsRecreate_ = true;  // minimised at start: created when the window shows
    return Status::success();
  }
  return recreate(size);
}

Swapchain::~Swapchain() {
  VkDevice dev = ctx_.device();
  vkDeviceWaitIdle(dev);
  destroyTargets();
  if (swapchain_) vkDestroySwapchainKHR(dev, swapchain_, nullptr);
  destroyBuffer(dev, captureBuffer_);
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    if (acquired_[i]) vkDestroySemaphore(dev, acquired_[i], nullptr);
    if (inFlight_[i]) vkDestroyFence(dev, inFlight_[i], nullptr);
  }
  if (pool_) vkDestroyCommandPool(dev, pool_, nullptr);
  if (renderPass_) vkDestroyRenderPass(dev, renderPass_, nullptr);
  if (loadPass_) vkDestroyRenderPass(dev, loadPass_, nullptr);
}

void Swapchain::destroyTargets() {
  VkDevice dev = ctx_.device();
  for (Image& img : hostImages_) destroyImage(dev, img);
  hostImages_.clear();
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    destroyBuffer(dev, hostReadback_[i]);
    hostPending_[i] = false;
  }
  for (VkFramebuffer fb : framebuffers_) vkDestroyFramebuffer(dev, fb, nullptr);
  for (VkImageView v : views_) vkDestroyImageView(dev, v, nullptr);
  for (VkSemaphore s : renderDone_) vkDestroySemaphore(dev, s, nullptr);
  framebuffers_.clear();
  views_.clear();
  renderDone_.clear();
  images_.clear();
  destroyImage(dev, depth_);
}

// A framebuffer of the render pass over `color` and the depth buffer, at the current extent.
Status Swapchain::addFramebuffer(VkImageView color) {
  Result<VkFramebuffer> fb = createSceneFramebuffer(ctx_.device(), renderPass_, color, depth_.view, extent_);
  if (!fb) return Error{fb.error()};
  framebuffers_.push_back(*fb);
  return Status::success();
}

// Host presentation: per frame slot a colour image (copied to a host buffer after the render
// pass), the shared depth buffer, the framebuffers, and the presenter's segments.
Status Swapchain::recreateHost(VkExtent2D size) {
  VkDevice dev = ctx_.device();
  vkDeviceWaitIdle(dev);
  destroyTargets();
  const size_t alignment = ctx_.supportsHostMemoryImport() ? size_t(ctx_.hostPointerAlignment()) : 4096;
  if (!host_->resize(size.width, size.height, kFramesInFlight, alignment))
    return Error{"MIT-SHM: " + host_->lastError()};
  // ANIMORPH_PRESENT=copy: host buffers copied by the CPU even where the segments could be imported (tests).
  const char* env = std::getenv("ANIMORPH_PRESENT");
  hostImported_ = ctx_.supportsHostMemoryImport() && !(env && std::string(env) == "copy");
  if (!hostImported_) presentPath_ = "MIT-SHM (host, copied)";
  extent_ = size;
  minImageCount_ = 2;
  captureSupported_ = true;
  Result<Image> depth =
      createImage(ctx_, extent_, ctx_.depthFormat(), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  if (!depth) return Error{depth.error()};
  depth_ = *depth;
  // The copies' destinations: each slot's shared segment itself when the device can import it,
  // else host buffers copied into the segments when the frames are put.
  for (uint32_t i = 0; i < kFramesInFlight && hostImported_; ++i) {
    Result<Buffer> rb = importHostBuffer(ctx_, host_->segment(i), host_->segmentBytes());
    if (rb) {
      hostReadback_[i] = *rb;
      continue;
    }
    for (uint32_t k = 0; k < i; ++k) destroyBuffer(dev, hostReadback_[k]);
    hostImported_ = false;
    presentPath_ = "MIT-SHM (host, copied: " + rb.error() + ")";
  }
  const VkDeviceSize bytes = VkDeviceSize(size.width) * size.height * 4;
  for (uint32_t i = 0; i < kFramesInFlight && !hostImported_; ++i) {
    Result<Buffer> rb = createHostBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (!rb) return Error{rb.error()};
    hostReadback_[i] = *rb;
  }
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    Result<Image> img = createImage(ctx_, extent_, format_.format,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                        VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                    VK_IMAGE_ASPECT_COLOR_BIT);
    if (!img) return Error{img.error()};
    hostImages_.push_back(*img);
    images_.push_back(img->image);
    Status st = addFramebuffer(img->view);
    if (!st) return st;
  }
  needsRecreate_ = false;
  return Status::success();
}

// Puts slot's finished frame (its fence has signalled) into the window.
Status Swapchain::flushPresentation() {
  if (!host_) return Status::success();
  for (uint32_t k = 0; k < kFramesInFlight; ++k) {  // oldest first: slot_ is the next to be used
    uint32_t s = (slot_ + k) % kFramesInFlight;
    if (!hostPending_[s]) continue;
    VkResult r = vkWaitForFences(ctx_.device(), 1, &inFlight_[s], VK_TRUE, UINT64_MAX);
    if (r != VK_SUCCESS) return vkError("vkWaitForFences", r);
    presentHost(s);
  }
  return Status::success();
}

void Swapchain::presentHost(uint32_t slot) {
  hostPending_[slot] = false;
  if (hostImported_) {  // the device's copy wrote the segment
    host_->present(slot);
    return;
  }
  uint8_t* dst = host_->pixels(slot);
  if (!dst) return;
  const auto* src = static_cast<const uint8_t*>(hostReadback_[slot].mapped);
  const size_t row = size_t(extent_.width) * 4, stride = host_->stride();
  if (stride == row) std::memcpy(dst, src, row * extent_.height);
  else
    for (uint32_t y = 0; y < extent_.height; ++y) std::memcpy(dst + y * stride, src + y * row, row);
  host_->present(slot);
}

Status Swapchain::recreate(VkExtent2D size) {
  if (host_) return recreateHost(size);
  VkDevice dev = ctx_.device();
  VkPhysicalDevice pd = ctx_.physicalDevice();
  VkSurfaceCapabilitiesKHR caps;
  AM_VK_TRY(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, ctx_.surface(), &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (caps.currentExtent.width != UINT32_MAX) size = caps.currentExtent;
  size.width = std::clamp(size.width, caps.minImageExtent.width, caps.maxImageExtent.width);
  size.height = std::clamp(size.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  if (size.width == 0 || size.height == 0) {  // minimised meanwhile: keep everything, try again later
    needsRecreate_ = true;
    return Status::success();
  }
  vkDeviceWaitIdle(dev);
  destroyTargets();
  uint32_t n = 0;
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, ctx_.surface(), &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, ctx_.surface(), &n, modes.data());
  presentMode_ = std::find(modes.begin(), modes.end(), toVk(settings_.presentMode)) != modes.end()
                     ? settings_.presentMode
                     : PresentMode::Fifo;
  uint32_t imageCount = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
  minImageCount_ = std::max(caps.minImageCount, 2u);
  captureSupported_ = caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  underlaySupported_ = caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT;

  VkSwapchainKHR old = swapchain_;
  VkSwapchainCreateInfoKHR sci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  sci.surface = ctx_.surface();
  sci.minImageCount = imageCount;
  sci.imageFormat = format_.format;
  sci.imageColorSpace = format_.colorSpace;
  sci.imageExtent = size;
  sci.imageArrayLayers = 1;
  sci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (captureSupported_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0) |
                   (underlaySupported_ ? VK_IMAGE_USAGE_TRANSFER_DST_BIT : 0);
  sci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  sci.preTransform = caps.currentTransform;
  sci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                           ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                           : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  sci.presentMode = toVk(presentMode_);
  sci.clipped = VK_TRUE;
  sci.oldSwapchain = old;
  VkResult r = vkCreateSwapchainKHR(dev, &sci, nullptr, &swapchain_);
  if (old) vkDestroySwapchainKHR(dev, old, nullptr);
  if (r != VK_SUCCESS) {
    swapchain_ = VK_NULL_HANDLE;
    return vkError("vkCreateSwapchainKHR " + std::to_string(size.width) + "x" + std::to_string(size.height), r);
  }
  extent_ = size;

  vkGetSwapchainImagesKHR(dev, swapchain_, &n, nullptr);
  images_.resize(n);
  vkGetSwapchainImagesKHR(dev, swapchain_, &n, images_.data());
  Result<Image> depth =
      createImage(ctx_, extent_, ctx_.depthFormat(), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  if (!depth) return Error{depth.error()};
  depth_ = *depth;
  for (VkImage img : images_) {
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = img;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format_.format;
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    AM_VK_TRY(vkCreateImageView(dev, &vci, nullptr, &view), "vkCreateImageView (swapchain)");
    views_.push_back(view);
    Status st = addFramebuffer(view);
    if (!st) return st;
    VkSemaphoreCreateInfo semi{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore sem = VK_NULL_HANDLE;
    AM_VK_TRY(vkCreateSemaphore(dev, &semi, nullptr, &sem), "vkCreateSemaphore");
    renderDone_.push_back(sem);
  }
  needsRecreate_ = false;
  return Status::success();
}

FrameStatus Swapchain::fail(const std::string& message) {
  lastError_ = message;
  return FrameStatus::Failed;
}

namespace {
// Testing the editor's recovery for real (lavapipe never loses its device): with
// ANIMORPH_DEBUG_DEVICE_LOST_FILE=PATH, the wait before the first frame that finds PATH existing
// reports VK_ERROR_DEVICE_LOST, once per process.
bool debugDeviceLostNow() {
  static const char* path = std::getenv("ANIMORPH_DEBUG_DEVICE_LOST_FILE");
  static bool fired = false;
  if (!path || fired || access(path, F_OK) != 0) return false;
  fired = true;
  return true;
}
}  // namespace

FrameStatus Swapchain::beginFrame(Frame& frame) {
  FrameStatus st = acquireFrame(frame);
  if (st == FrameStatus::Ready) beginPass(nullptr);
  return st;
}

FrameStatus Swapchain::acquireFrame(Frame& frame) {
  VkDevice dev = ctx_.device();
  if (frameOpen_) return fail("beginFrame called twice without endFrame");
  VkExtent2D size = framebufferSize(ctx_.window());
  if (size.width == 0 || size.height == 0) return FrameStatus::Skipped;  // minimised
  VkResult r = vkWaitForFences(dev, 1, &inFlight_[slot_], VK_TRUE, UINT64_MAX);
  if (r == VK_SUCCESS && debugDeviceLostNow()) r = VK_ERROR_DEVICE_LOST;
  if (r != VK_SUCCESS) return fail(vkError("vkWaitForFences", r).message);
  if (host_) {
    // This frame's copy writes the slot's segment: the server must have read the frame put there
    // two frames ago (a round trip, before the previous frame is put, so as not to wait for that).
    if (hostImported_) host_->sync();
    // The previous frame, submitted before this one's UI work: put it into the window now.
    for (uint32_t k = 1; k < kFramesInFlight; ++k) {
      uint32_t prev = (slot_ + kFramesInFlight - k) % kFramesInFlight;
      if (!hostPending_[prev]) continue;
      r = vkWaitForFences(dev, 1, &inFlight_[prev], VK_TRUE, UINT64_MAX);
      if (r != VK_SUCCESS) return fail(vkError("vkWaitForFences", r).message);
      presentHost(prev);
    }
    if (hostPending_[slot_]) presentHost(slot_);
    if (needsRecreate_ || hostImages_.empty() || size.width != extent_.width || size.height != extent_.height) {
      Status s = recreate(size);
      if (!s) return fail(s.error());
    }
    imageIndex_ = slot_;
  } else {
  if (needsRecreate_ || !swapchain_ || size.width != extent_.width || size.height != extent_.height) {
    Status s = recreate(size);
    if (!s) return fail(s.error());
    if (needsRecreate_ || !swapchain_) return FrameStatus::Skipped;  // surface reports 0x0
  }
  r = vkAcquireNextImageKHR(dev, swapchain_, UINT64_MAX, acquired_[slot_], VK_NULL_HANDLE, &imageIndex_);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) {
    needsRecreate_ = true;
    return FrameStatus::Skipped;
  }
  if (r == VK_SUBOPTIMAL_KHR) needsRecreate_ = true;  // still usable for this frame
  else if (r != VK_SUCCESS) return fail(vkError("vkAcquireNextImageKHR", r).message);
  }

  VkCommandBuffer cmd = cmds_[slot_];
  vkResetFences(dev, 1, &inFlight_[slot_]);
  vkResetCommandBuffer(cmd, 0);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &bi);
  frame = Frame{cmd, serial_, slot_, imageIndex_, extent_};
  frameOpen_ = true;
  passOpen_ = false;
  return FrameStatus::Ready;
}

namespace {

// Inside a render pass over the whole frame image: up to four bands around rect (clipped to the
// frame) cleared to c; with the copied rectangle they cover the window once.
void clearAroundUnderlay(VkCommandBuffer cmd, VkExtent2D extent, const VkRect2D& rect, const glm::vec4& c) {
  const int32_t w = int32_t(extent.width), h = int32_t(extent.height);
  const int32_t x0 = std::clamp(rect.offset.x, 0, w), y0 = std::clamp(rect.offset.y, 0, h);
  const int32_t x1 = std::clamp(rect.offset.x + int32_t(rect.extent.width), x0, w);
  const int32_t y1 = std::clamp(rect.offset.y + int32_t(rect.extent.height), y0, h);
  VkClearRect bands[4]{};
  uint32_t n = 0;
  auto add = [&](int32_t x, int32_t y, int32_t bw, int32_t bh) {
    if (bw > 0 && bh > 0) bands[n++] = VkClearRect{{{x, y}, {uint32_t(bw), uint32_t(bh)}}, 0, 1};
  };
  add(0, 0, w, y0);              // above
  add(0, y1, w, h - y1);         // below
  add(0, y0, x0, y1 - y0);       // left
  add(x1, y0, w - x1, y1 - y0);  // right
  if (n == 0) return;
  VkClearAttachment clear{};
  clear.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
  clear.colorAttachment = 0;
  clear.clearValue.color = {{c.r, c.g, c.b, c.a}};
  vkCmdClearAttachments(cmd, 1, &clear, n, bands);
}

}  // namespace

// The underlay's image copied into its rectangle of the frame image, which then waits for the pass
// that loads it (the window around the rectangle is cleared in that pass: clearAroundUnderlay).
void Swapchain::recordUnderlay(VkCommandBuffer cmd, const FrameUnderlay& u) {
  VkImage target = host_ ? hostImages_[slot_].image : images_[imageIndex_];
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = target;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.srcAccessMask = 0;
  b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  // After the previous use of this image (its pass, its copy to the host, its presentation).
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
  // The rest of the window is cleared inside the pass (clearAroundUnderlay): the rectangle the copy
  // fills is not written twice (on a CPU device a clear is a memset of every pixel).
  VkImageCopy region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstSubresource = region.srcSubresource;
  region.dstOffset = {u.rect.offset.x, u.rect.offset.y, 0};
  region.extent = {u.rect.extent.width, u.rect.extent.height, 1};
  vkCmdCopyImage(cmd, u.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                 &region);
  b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0, nullptr,
                       0, nullptr, 1, &b);
}

void Swapchain::beginPass(const FrameUnderlay* underlay) {
  if (!frameOpen_ || passOpen_) return;
  VkCommandBuffer cmd = cmds_[slot_];
  const bool load = underlay && underlay->image && underlaySupported();
  if (load) recordUnderlay(cmd, *underlay);
  const glm::vec4& c = settings_.clearColor;
  const float clear[4] = {c.r, c.g, c.b, c.a};
  beginScenePass(cmd, load ? loadPass_ : renderPass_, framebuffers_[imageIndex_], extent_, clear);
  if (load) clearAroundUnderlay(cmd, extent_, underlay->rect, settings_.clearColor);
  passOpen_ = true;
}

Status Swapchain::endFrame() {
  if (!frameOpen_) return Error{"endFrame without a successful beginFrame"};
  frameOpen_ = false;
  VkDevice dev = ctx_.device();
  VkCommandBuffer cmd = cmds_[slot_];
  if (!passOpen_) beginPass(nullptr);  // acquired, but nothing drawn: the window cleared
  vkCmdEndRenderPass(cmd);
  passOpen_ = false;
  if (host_) return endFrameHost(cmd);

  captureRecorded_ = false;
  if (captureRequested_ && captureSupported_) {
    VkDeviceSize bytes = VkDeviceSize(extent_.width) * extent_.height * 4;
    if (captureBuffer_.size < bytes) {
      destroyBuffer(dev, captureBuffer_);
      Result<Buffer> b = createHostBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
      if (b) captureBuffer_ = *b;
      else lastError_ = "capture: " + b.error();
    }
    if (captureBuffer_.buffer) {
      VkImageMemoryBarrier toSrc{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      toSrc.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
      toSrc.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
      toSrc.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
      toSrc.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
      toSrc.srcQueueFamilyIndex = toSrc.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      toSrc.image = images_[imageIndex_];
      toSrc.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                           nullptr, 0, nullptr, 1, &toSrc);
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {extent_.width, extent_.height, 1};
      vkCmdCopyImageToBuffer(cmd, images_[imageIndex_], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, captureBuffer_.buffer, 1,
                             &region);
      VkImageMemoryBarrier toPresent = toSrc;
      toPresent.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
      toPresent.dstAccessMask = 0;
      toPresent.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
      toPresent.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
      VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
      toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      toHost.buffer = captureBuffer_.buffer;
      toHost.size = VK_WHOLE_SIZE;
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &toHost,
                           1, &toPresent);
      captureRecorded_ = true;
    }
    captureRequested_ = false;
  }

  AM_VK_TRY(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  // The underlay's clear and copy (beginPass) write the acquired image too.
  VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &acquired_[slot_];
  si.pWaitDstStageMask = &waitStage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &renderDone_[imageIndex_];
  VkResult r = vkQueueSubmit(ctx_.queue(), 1, &si, inFlight_[slot_]);
  if (r != VK_SUCCESS) {
    lastError_ = vkError("vkQueueSubmit", r).message;
    return Error{lastError_};
  }
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &renderDone_[imageIndex_];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &imageIndex_;
  r = vkQueuePresentKHR(ctx_.queue(), &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) needsRecreate_ = true;
  else if (r != VK_SUCCESS) {
    lastError_ = vkError("vkQueuePresentKHR", r).message;
    return Error{lastError_};
  }

  if (captureRecorded_) {
    vkWaitForFences(dev, 1, &inFlight_[slot_], VK_TRUE, UINT64_MAX);
    RgbaImage img;
    img.width = extent_.width;
    img.height = extent_.height;
    img.pixels.resize(size_t(img.width) * img.height * 4);
    std::memcpy(img.pixels.data(), captureBuffer_.mapped, img.pixels.size());
    if (isBgra(format_.format))
      for (size_t i = 0; i < img.pixels.size(); i += 4) std::swap(img.pixels[i], img.pixels[i + 2]);
    for (size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 255;  // the window is opaque
    capture_ = std::move(img);
  }
  ++serial_;
  slot_ = static_cast<uint32_t>(serial_ % kFramesInFlight);
  return Status::success();
}

// Host presentation: the image (TRANSFER_SRC after the render pass) goes to the slot's host
// buffer; the next beginFrame puts it into the window (a capture waits and puts it now).
Status Swapchain::endFrameHost(VkCommandBuffer cmd) {
  VkDevice dev = ctx_.device();
  VkBufferImageCopy region{};
  if (hostImported_) region.bufferRowLength = host_->stride() / 4;  // the segment's rows
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyImageToBuffer(cmd, hostImages_[slot_].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, hostReadback_[slot_].buffer,
                         1, &region);
  VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toHost.buffer = hostReadback_[slot_].buffer;
  toHost.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &toHost, 0,
                       nullptr);
  AM_VK_TRY(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  VkResult r = vkQueueSubmit(ctx_.queue(), 1, &si, inFlight_[slot_]);
  if (r != VK_SUCCESS) {
    lastError_ = vkError("vkQueueSubmit", r).message;
    return Error{lastError_};
  }
  hostPending_[slot_] = true;
  if (captureRequested_) {
    captureRequested_ = false;
    vkWaitForFences(dev, 1, &inFlight_[slot_], VK_TRUE, UINT64_MAX);
    RgbaImage img;
    img.width = extent_.width;
    img.height = extent_.height;
    img.pixels.resize(size_t(img.width) * img.height * 4);
    const uint8_t* src = hostImported_ ? host_->segment(slot_) : static_cast<const uint8_t*>(hostReadback_[slot_].mapped);
    const size_t row = size_t(img.width) * 4, stride = hostImported_ ? host_->stride() : row;
    for (uint32_t y = 0; y < img.height; ++y) std::memcpy(img.pixels.data() + y * row, src + y * stride, row);
    for (size_t i = 0; i < img.pixels.size(); i += 4) {
      std::swap(img.pixels[i], img.pixels[i + 2]);  // BGRA -> RGBA
      img.pixels[i + 3] = 255;                      // the window is opaque
    }
    capture_ = std::move(img);
    presentHost(slot_);
  }
  ++serial_;
  slot_ = static_cast<uint32_t>(serial_ % kFramesInFlight);
  return Status::success();
}

std::optional<RgbaImage> Swapchain::takeCapture() {
  std::optional<RgbaImage> out = std::move(capture_);
  capture_.reset();
  return out;
}

}  // namespace animorph::gpu
