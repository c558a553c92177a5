#include "gpu/present/x11_shm_presenter.h"

#if ANIMORPH_HAS_X11_SHM
#include <sys/ipc.h>
#include <sys/shm.h>

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>
#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3.h>
#include <GLFW/glfw3native.h>

#include <vector>
#endif

namespace animorph::gpu {

#if ANIMORPH_HAS_X11_SHM
namespace {
// XShmAttach reports a refusal (a remote display) as an asynchronous X error; this catches it.
bool g_xError = false;
int catchXError(Display*, XErrorEvent*) {
  g_xError = true;
  return 0;
}
}  // namespace

struct X11ShmPresenter::Impl {
  Display* dpy = nullptr;
  Window win = 0;
  Visual* visual = nullptr;
  int depth = 0;
  GC gc = nullptr;
  struct Slot {
    XImage* image = nullptr;
    XShmSegmentInfo shm{};
  };
  std::vector<Slot> slots;
  uint32_t width = 0, height = 0;
  size_t bytes = 0;       // of each segment
  bool unsynced = false;  // a put was sent since the last XSync

  void freeSlots() {
    if (slots.empty()) return;
    XSync(dpy, False);
    for (Slot& s : slots) {
      if (s.shm.shmaddr) XShmDetach(dpy, &s.shm);
      if (s.image) {
        s.image->data = nullptr;
        XDestroyImage(s.image);
      }
      if (s.shm.shmaddr) shmdt(s.shm.shmaddr);
    }
    XSync(dpy, False);
    slots.clear();
    unsynced = false;
  }
};

X11ShmPresenter::X11ShmPresenter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

X11ShmPresenter::~X11ShmPresenter() {
  if (!impl_) return;
  impl_->freeSlots();
  if (impl_->gc) XFreeGC(impl_->dpy, impl_->gc);
}

std::unique_ptr<X11ShmPresenter> X11ShmPresenter::create(GLFWwindow* window, std::string& why) {
  auto impl = std::make_unique<Impl>();
  impl->dpy = glfwGetX11Display();
  impl->win = window ? glfwGetX11Window(window) : 0;
  if (!impl->dpy || !impl->win) {
    why = "not an X11 window";
    return nullptr;
  }
  int major = 0, minor = 0;
  Bool pixmaps = False;
  if (!XShmQueryVersion(impl->dpy, &major, &minor, &pixmaps)) {
    why = "the X server has no MIT-SHM";
    return nullptr;
  }
  XWindowAttributes attrs{};
  if (!XGetWindowAttributes(impl->dpy, impl->win, &attrs) || !attrs.visual) {
    why = "the window's visual is unknown";
    return nullptr;
  }
  // The frame is B8G8R8A8 in memory: a 32-bit little-endian pixel with red at bits 16..23.
  const Visual* v = attrs.visual;
  if ((attrs.depth != 24 && attrs.depth != 32) || v->red_mask != 0xff0000 || v->green_mask != 0xff00 ||
      v->blue_mask != 0xff || ImageByteOrder(impl->dpy) != LSBFirst) {
    why = "the window's visual is not 24-bit BGRX";
    return nullptr;
  }
  impl->visual = attrs.visual;
  impl->depth = attrs.depth;
  impl->gc = XCreateGC(impl->dpy, impl->win, 0, nullptr);
  std::unique_ptr<X11ShmPresenter> p(new X11ShmPresenter(std::move(impl)));
  // Try one small segment: a remote server refuses to attach.
  if (!p->resize(16, 16, 1)) {
    why = p->lastError();
    return nullptr;
  }
  return p;
}

bool X11ShmPresenter::resize(uint32_t width, uint32_t height, uint32_t slots, size_t alignment) {
  Impl& m = *impl_;
  m.freeSlots();
  m.width = width;
  m.height = height;
  g_xError = false;
  XErrorHandler previous = XSetErrorHandler(catchXError);
  bool ok = true;
  // XShmCreateImage keeps a pointer to the slot's XShmSegmentInfo: the slots must not move.
  m.slots.resize(slots);
  for (uint32_t i = 0; i < slots && ok; ++i) {
    Impl::Slot& s = m.slots[i];
    s.image = XShmCreateImage(m.dpy, m.visual, unsigned(m.depth), ZPixmap, nullptr, &s.shm, width, height);
    if (!s.image || s.image->bits_per_pixel != 32) {
      error_ = "XShmCreateImage failed";
      ok = false;
      break;
    }
    alignment = alignment ? alignment : 1;
    m.bytes = (size_t(s.image->bytes_per_line) * height + alignment - 1) / alignment * alignment;
    s.shm.shmid = shmget(IPC_PRIVATE, m.bytes, IPC_CREAT | 0600);
    if (s.shm.shmid < 0) {
      error_ = "shmget failed";
      ok = false;
      break;
    }
    void* addr = shmat(s.shm.shmid, nullptr, 0);
    if (addr == reinterpret_cast<void*>(-1)) {
      shmctl(s.shm.shmid, IPC_RMID, nullptr);
      error_ = "shmat failed";
      ok = false;
      break;
    }
    s.shm.readOnly = False;
    XShmAttach(m.dpy, &s.shm);
    XSync(m.dpy, False);
    shmctl(s.shm.shmid, IPC_RMID, nullptr);  // freed once both sides detach
    s.shm.shmaddr = s.image->data = static_cast<char*>(addr);
    if (g_xError) {
      error_ = "the X server refused the shared memory (remote display?)";
      ok = false;
    }
  }
  if (!ok) m.freeSlots();  // still under catchXError: detaching a refused segment is an error too
  XSetErrorHandler(previous);
  return ok;
}

void X11ShmPresenter::sync() {
  Impl& m = *impl_;
  if (m.unsynced) {  // the server may still be reading a segment: a round trip makes sure it is done
    XSync(m.dpy, False);
    m.unsynced = false;
  }
}

uint8_t* X11ShmPresenter::pixels(uint32_t slot) {
  Impl& m = *impl_;
  if (slot >= m.slots.size()) return nullptr;
  sync();
  return reinterpret_cast<uint8_t*>(m.slots[slot].image->data);
}

uint8_t* X11ShmPresenter::segment(uint32_t slot) const {
  return slot < impl_->slots.size() ? reinterpret_cast<uint8_t*>(impl_->slots[slot].image->data) : nullptr;
}

size_t X11ShmPresenter::segmentBytes() const { return impl_->bytes; }

uint32_t X11ShmPresenter::stride() const {
  return impl_->slots.empty() ? 0u : uint32_t(impl_->slots.front().image->bytes_per_line);
}

bool X11ShmPresenter::present(uint32_t slot) {
  Impl& m = *impl_;
  if (slot >= m.slots.size()) return false;
  XShmPutImage(m.dpy, m.win, m.gc, m.slots[slot].image, 0, 0, 0, 0, m.width, m.height, False);
  XFlush(m.dpy);
  m.unsynced = true;
  return true;
}

#else

struct X11ShmPresenter::Impl {};
X11ShmPresenter::X11ShmPresenter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
X11ShmPresenter::~X11ShmPresenter() = default;
std::unique_ptr<X11ShmPresenter> X11ShmPresenter::create(GLFWwindow*, std::string& why) {
  why = "built without Xlib/Xext";
  return nullptr;
}
bool X11ShmPresenter::resize(uint32_t, uint32_t, uint32_t, size_t) { return false; }
uint8_t* X11ShmPresenter::pixels(uint32_t) { return nullptr; }
uint8_t* X11ShmPresenter::segment(uint32_t) const { return nullptr; }
size_t X11ShmPresenter::segmentBytes() const { return 0; }
void X11ShmPresenter::sync() {}
uint32_t X11ShmPresenter::stride() const { return 0; }
bool X11ShmPresenter::present(uint32_t) { return false; }

#endif

}  // namespace animorph::gpu
