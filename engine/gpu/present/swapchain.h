#pragma once
// Presenting to the context's window: swapchain (recreated on resize), depth
// buffer, render pass, kFramesInFlight frames in flight, and a frame capture.
//
// Editor frame:
//   gpu::Frame f;
//   if (swapchain.beginFrame(f) == gpu::FrameStatus::Ready) {
//     sceneRenderer.record(f.cmd, f.serial, viewportRect, camera, scene);  // 3D into a rectangle
//     imguiVulkan.record(f.cmd, f.slot);                                 // same render pass (ui/)
//     swapchain.endFrame();
//   }
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "gpu/vulkan/image.h"
#include "gpu/present/rgba_image.h"
#include "shared_constants.h"
#include "gpu/present/x11_shm_presenter.h"

namespace animorph::gpu {

enum class PresentMode {
  Fifo,       // vsync, always available (default)
  Mailbox,    // low latency without tearing, for benchmarks; falls back to Fifo
  Immediate,  // no vsync, may tear, for benchmarks; falls back to Fifo
};

struct SwapchainSettings {
  PresentMode presentMode = PresentMode::Fifo;
  // On a CPU Vulkan device (lavapipe) with an X11 window: render into our own images and put
  // them into the window through MIT-SHM (x11_shm_presenter.h) instead of the Vulkan WSI, whose
  // software path sends every frame through the X socket when the server has no DRI3 (Xvfb,
  // Xvnc, xrdp). ANIMORPH_PRESENT=wsi in the environment turns it off.
  bool hostPresent = true;
  glm::vec4 clearColor{0.11f, 0.11f, 0.12f, 1.0f};  // the whole window, before UI and 3D
};

// One frame being recorded: the render pass is active on cmd over the whole image.
struct Frame {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  uint64_t serial = 0;      // number of this frame (counts Ready frames), for SceneRenderer::record
  uint32_t slot = 0;        // frame-in-flight slot: serial % kFramesInFlight
  uint32_t imageIndex = 0;  // swapchain image
  VkExtent2D extent{0, 0};  // pixels of the window's framebuffer
};

// An image copied into a frame before its render pass (the kept viewport image, viewport_image.h):
// same format as the swapchain, in TRANSFER_SRC_OPTIMAL, rect inside both images.
struct FrameUnderlay {
  VkImage image = VK_NULL_HANDLE;
  VkRect2D rect{};
};

enum class FrameStatus {
  Ready,    // record into the Frame, then call endFrame()
  Skipped,  // minimised (0x0) or the swapchain was just recreated: draw nothing this time
  Failed,   // lastError() says why (device lost, surface lost); the caller may retry later
};

class Swapchain {
 public:
  // Needs a windowed Context. Errors: surface unusable, Vulkan failures.
  static Result<std::unique_ptr<Swapchain>> create(Context& ctx, const SwapchainSettings& settings = {});
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // Waits for the frame slot, recreates the swapchain when the window size
  // changed, acquires an image, begins the command buffer and the render pass.
  FrameStatus beginFrame(Frame& frame);
  // beginFrame in two steps, for commands recorded before the render pass (an offscreen pass):
  // acquireFrame waits, acquires and begins the command buffer (no render pass yet); beginPass then
  // begins the render pass over the whole image: cleared, or with underlay the window cleared and
  // the underlay's image copied into its rectangle, then loaded (needs underlaySupported(), else
  // the underlay is ignored). endFrame begins the pass itself when beginPass was not called.
  FrameStatus acquireFrame(Frame& frame);
  void beginPass(const FrameUnderlay* underlay);
  // The frame images can be copied into (TRANSFER_DST on the swapchain images or our own).
  bool underlaySupported() const { return host_ || underlaySupported_; }
  // Ends the render pass, records the capture if one was requested, submits and
  // presents. An out-of-date swapchain is recreated on the next beginFrame.
  // Errors: Vulkan failures (also in lastError()).
  Status endFrame();

  // Makes the next endFrame() copy its image to host memory (RGBA8); fetch it
  // with takeCapture() after that endFrame(). Needs TRANSFER_SRC support on the
  // swapchain images (without it the request is ignored).
  void requestCapture() { captureRequested_ = true; }
  // Puts the frames still waiting for the window into it now (host presentation puts a frame at
  // the next beginFrame; call this before waiting for events). No-op on the WSI path.
  Status flushPresentation();
  // The captured image, once; nullopt when none was taken since the last call.
  std::optional<RgbaImage> takeCapture();

  // For the UI and scene renderers' pipelines.
  VkRenderPass renderPass() const { return renderPass_; }
  uint32_t imageCount() const { return static_cast<uint32_t>(images_.size()); }
  uint32_t minImageCount() const { return minImageCount_; }
  VkFormat colorFormat() const { return format_.format; }
  VkExtent2D extent() const { return extent_; }
  PresentMode presentMode() const { return presentMode_; }  // the one in use after fallback
  const std::string& lastError() const { return lastError_; }
  // How frames reach the window: "Vulkan WSI" or "MIT-SHM (host)", and why not MIT-SHM.
  const std::string& presentPath() const { return presentPath_; }

 private:
  explicit Swapchain(Context& ctx) : ctx_(ctx) {}
  Status init(const SwapchainSettings& settings);
  Status recreate(VkExtent2D framebufferSize);
  void destroyTargets();
  Status recreateHost(VkExtent2D size);
  Status addFramebuffer(VkImageView color);
  Status endFrameHost(VkCommandBuffer cmd);
  void presentHost(uint32_t slot);
  void recordUnderlay(VkCommandBuffer cmd, const FrameUnderlay& underlay);
  FrameStatus fail(const std::string& message);

  Context& ctx_;
  SwapchainSettings settings_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkSurfaceFormatKHR format_{};
  PresentMode presentMode_ = PresentMode::Fifo;
  VkExtent2D extent_{0, 0};
  uint32_t minImageCount_ = 2;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkRenderPass loadPass_ = VK_NULL_HANDLE;  // compatible with renderPass_: the colour loaded (beginPass)
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  std::vector<VkSemaphore> renderDone_;  // per image: signalled by the submit, waited by present
  Image depth_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmds_[kFramesInFlight]{};
  VkSemaphore acquired_[kFramesInFlight]{};
  VkFence inFlight_[kFramesInFlight]{};
  uint32_t slot_ = 0;
  uint64_t serial_ = 0;  // frames begun (Ready) so far; slot_ == serial_ % kFramesInFlight
  uint32_t imageIndex_ = 0;
  bool frameOpen_ = false;
  bool passOpen_ = false;
  bool underlaySupported_ = false;  // WSI images take TRANSFER_DST
  bool needsRecreate_ = false;
  bool captureSupported_ = false;
  bool captureRequested_ = false;
  bool captureRecorded_ = false;
  Buffer captureBuffer_;
  std::optional<RgbaImage> capture_;
  std::string lastError_;
  std::string presentPath_;
  // Host presentation (hostPresent): per frame slot our own colour image, the buffer it is copied
  // into, and whether that frame still has to be put into the window.
  std::unique_ptr<X11ShmPresenter> host_;
  std::vector<Image> hostImages_;
  Buffer hostReadback_[kFramesInFlight];
  bool hostPending_[kFramesInFlight]{};
  bool hostImported_ = false;  // hostReadback_ are the presenter's segments (VK_EXT_external_memory_host)
};

}  // namespace animorph::gpu
