#include "app/editor/editor_window.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdio>

#include "ui/shell/editor_ui.h"
#include "core/poly/preview_polygonizer.h"
#include "app/editor/window_events.h"

namespace animorph {

GLFWwindow* openEditorWindow(int width, int height) {
  if (!glfwInit()) {
    std::fprintf(stderr, "animorph: cannot open a window (no display?). Run under a virtual X server:\n"
                         "  xvfb-run -a animorph ...   or use animorph-cli for headless work.\n");
    return nullptr;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window = glfwCreateWindow(width, height, "Animorph", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "animorph: could not create a window\n");
    glfwTerminate();
    return nullptr;
  }
  watchWindowEvents(window);  // before ImGui's backend, which chains to these callbacks
  PreviewPolygonizer::setPublishHook([] { glfwPostEmptyEvent(); });  // a preview mesh wakes the frame loop
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout lives in our preferences
  EditorUI::applyStyle();                // before the swapchain: the window is cleared to the panels' colour
  return window;
}

gpu::SwapchainSettings editorSwapchainSettings(bool bench) {
  gpu::SwapchainSettings ss;
  float c[4];
  EditorUI::windowClearColor(c);
  ss.clearColor = glm::vec4(c[0], c[1], c[2], c[3]);
  if (bench) ss.presentMode = gpu::PresentMode::Immediate;
  return ss;
}

void closeEditorWindow(GLFWwindow* window) {
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
}

}  // namespace animorph
