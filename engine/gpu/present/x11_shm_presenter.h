#pragma once
// Putting finished frames into an X11 window through MIT-SHM shared memory, for
// CPU Vulkan devices (lavapipe). Mesa's software WSI uses MIT-SHM only when the
// X server also has DRI3; without it (Xvfb, Xvnc, xrdp: the usual X servers of
// machines without a GPU) each frame is an XPutImage of the whole window
// through the X socket, which cost ~10 ms of CPU a frame at 1600x900 between the
// editor and the X server. Here the frame's bytes go into a shared segment and
// the server copies them from there (Swapchain's host-present mode).
//
// Each slot is one shared segment of the window's size, BGRX rows (B8G8R8A8).
#include <cstdint>
#include <memory>
#include <string>

struct GLFWwindow;

namespace animorph::gpu {

class X11ShmPresenter {
 public:
  // Null, with the reason in `why`, when the window is not on X11, the server has
  // no MIT-SHM (or refuses to attach: a remote display), or its visual is not
  // 24/32-bit BGRX. Built without Xlib/Xext: always null.
  static std::unique_ptr<X11ShmPresenter> create(GLFWwindow* window, std::string& why);
  ~X11ShmPresenter();
  X11ShmPresenter(const X11ShmPresenter&) = delete;
  X11ShmPresenter& operator=(const X11ShmPresenter&) = delete;

  // (Re)creates `slots` segments of width x height, each a multiple of `alignment`
  // bytes long (so a Vulkan buffer can import it). False (and lastError()) when the
  // server refuses them.
  bool resize(uint32_t width, uint32_t height, uint32_t slots, size_t alignment = 4096);
  // Slot's segment and its length in bytes (stride() x height, rounded up to the alignment).
  uint8_t* segment(uint32_t slot) const;
  size_t segmentBytes() const;
  // Waits until the server has finished reading every segment sent so far (before they are
  // written again, by the CPU or by a device copy).
  void sync();
  // Where to write slot's pixels: height rows of stride() bytes. Waits until the
  // server has finished reading the slot's previous frame.
  uint8_t* pixels(uint32_t slot);
  uint32_t stride() const;
  // Sends slot's pixels to the window (does not wait for the server).
  bool present(uint32_t slot);
  const std::string& lastError() const { return error_; }

 private:
  struct Impl;
  explicit X11ShmPresenter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  std::string error_;
};

}  // namespace animorph::gpu
