#include "app/editor/window_events.h"

#include <GLFW/glfw3.h>

#include <atomic>

namespace animorph {
namespace {

std::atomic<uint64_t> g_events{0};
std::vector<std::string> g_dropped;  // GLFW calls back on the main thread, in glfwPollEvents

void count() { g_events.fetch_add(1, std::memory_order_relaxed); }

}  // namespace

void watchWindowEvents(GLFWwindow* w) {
  // Input. ImGui 1.86 reads the cursor position each frame and has no callback for it.
  glfwSetCursorPosCallback(w, [](GLFWwindow*, double, double) { count(); });
  glfwSetCursorEnterCallback(w, [](GLFWwindow*, int) { count(); });
  glfwSetMouseButtonCallback(w, [](GLFWwindow*, int, int, int) { count(); });
  glfwSetScrollCallback(w, [](GLFWwindow*, double, double) { count(); });
  glfwSetKeyCallback(w, [](GLFWwindow*, int, int, int, int) { count(); });
  glfwSetCharCallback(w, [](GLFWwindow*, unsigned int) { count(); });
  glfwSetDropCallback(w, [](GLFWwindow*, int n, const char** paths) {
    count();
    for (int i = 0; i < n; ++i) g_dropped.emplace_back(paths[i]);
  });
  // The window: size, exposure (the X server keeps no copy of the contents), focus, state.
  glfwSetWindowSizeCallback(w, [](GLFWwindow*, int, int) { count(); });
  glfwSetFramebufferSizeCallback(w, [](GLFWwindow*, int, int) { count(); });
  glfwSetWindowRefreshCallback(w, [](GLFWwindow*) { count(); });
  glfwSetWindowFocusCallback(w, [](GLFWwindow*, int) { count(); });
  glfwSetWindowIconifyCallback(w, [](GLFWwindow*, int) { count(); });
  glfwSetWindowMaximizeCallback(w, [](GLFWwindow*, int) { count(); });
  glfwSetWindowContentScaleCallback(w, [](GLFWwindow*, float, float) { count(); });
}

uint64_t windowEventCount() { return g_events.load(std::memory_order_relaxed); }

std::vector<std::string> takeDroppedPaths() {
  std::vector<std::string> out;
  out.swap(g_dropped);
  return out;
}

}  // namespace animorph
