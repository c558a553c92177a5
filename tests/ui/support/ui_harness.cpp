#include "ui_harness.h"

#include <stdexcept>

#include <imgui.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace animorph::test {

EditorHarness::EditorHarness(const std::string& prefsPath, glm::vec2 display)
    : document(std::make_unique<Document>()), ctx(document, assets) {
  IMGUI_CHECKVERSION();
  imgui_ = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  io.DisplaySize = ImVec2(display.x, display.y);
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  // As the editor's renderer (gpu/present/imgui_vulkan.cpp): draw lists past 64K vertices (the
  // animorphosis demo's thousands of wires) are split by vertex offsets, not refused.
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;
  // The GLFW backend's key map (imgui_impl_glfw.cpp, 1.86).
  io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
  io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
  io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
  io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
  io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
  io.KeyMap[ImGuiKey_PageUp] = GLFW_KEY_PAGE_UP;
  io.KeyMap[ImGuiKey_PageDown] = GLFW_KEY_PAGE_DOWN;
  io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
  io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
  io.KeyMap[ImGuiKey_Insert] = GLFW_KEY_INSERT;
  io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
  io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
  io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
  io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
  io.KeyMap[ImGuiKey_KeyPadEnter] = GLFW_KEY_KP_ENTER;
  io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
  io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
  io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
  io.KeyMap[ImGuiKey_Y] = GLFW_KEY_Y;
  io.KeyMap[ImGuiKey_Z] = GLFW_KEY_Z;
  io.MousePos = ImVec2(display.x * 0.5f, display.y * 0.5f);
  ui = std::make_unique<EditorUI>(prefsPath);
  ctx.stats = {60.0f, 16.7f, "test device", ""};
  frames(2);  // windows exist and are laid out
}

EditorHarness::~EditorHarness() { ImGui::DestroyContext(imgui_); }

void EditorHarness::frame(double dtSec) {
  ImGuiIO& io = ImGui::GetIO();
  io.DeltaTime = static_cast<float>(dtSec);
  nowSec += dtSec;
  ctx.nowSec = nowSec;
  ctx.dtSec = dtSec;
  ImGui::NewFrame();
  ui->draw(ctx);
  ImGui::Render();
  if (finishJobs && ui->runningJob()) ui->finishJob(ctx);  // a frame's background work is done by the next frame
  io.MouseWheel = 0.0f;
}

void EditorHarness::frames(int n, double dtSec) {
  for (int i = 0; i < n; ++i) frame(dtSec);
}

void EditorHarness::moveTo(glm::vec2 p) {
  ImGui::GetIO().MousePos = ImVec2(p.x, p.y);
  frames(1);
}

void EditorHarness::press(int button) {
  ImGui::GetIO().MouseDown[button] = true;
  frames(1);
}

void EditorHarness::release(int button) {
  ImGui::GetIO().MouseDown[button] = false;
  frames(1);
}

void EditorHarness::settle() {
  // Longer than ImGui's double-click time: separate interactions stay separate.
  frames(1, 0.35);
}

void EditorHarness::click(glm::vec2 p, int button) {
  settle();
  moveTo(p);
  press(button);
  release(button);
}

void EditorHarness::doubleClick(glm::vec2 p) {
  settle();
  moveTo(p);
  press(0);
  release(0);
  press(0);
  release(0);
}

void EditorHarness::drag(glm::vec2 from, glm::vec2 to, int button, int steps) {
  settle();
  moveTo(from);
  press(button);
  for (int i = 1; i <= steps; ++i) moveTo(from + (to - from) * (static_cast<float>(i) / steps));
  release(button);
}

void EditorHarness::wheel(glm::vec2 p, float notches) {
  ImGui::GetIO().MousePos = ImVec2(p.x, p.y);
  ImGui::GetIO().MouseWheel = notches;
  frames(1);
}

void EditorHarness::setModifiers(bool ctrl, bool shift, bool alt) {
  ImGuiIO& io = ImGui::GetIO();
  io.KeyCtrl = ctrl;
  io.KeyShift = shift;
  io.KeyAlt = alt;
  io.KeysDown[GLFW_KEY_LEFT_CONTROL] = ctrl;
  io.KeysDown[GLFW_KEY_LEFT_SHIFT] = shift;
  io.KeysDown[GLFW_KEY_LEFT_ALT] = alt;
}

void EditorHarness::tapKey(int key, bool ctrl, bool shift, bool alt) {
  ImGuiIO& io = ImGui::GetIO();
  setModifiers(ctrl, shift, alt);
  io.KeysDown[key] = true;
  frames(1);
  io.KeysDown[key] = false;
  setModifiers(false, false, false);
  frames(1);
}

void EditorHarness::type(const std::string& utf8) {
  frames(1);  // a field focused by the last frame takes its keyboard focus now
  ImGui::GetIO().AddInputCharactersUTF8(utf8.c_str());
  frames(1);
}

glm::vec2 EditorHarness::widgetCenter(const std::string& key) const {
  auto r = ui->widgets().find(key);
  if (!r) throw std::runtime_error("widget not drawn in the last frame: " + key);
  return r->center();
}

}  // namespace animorph::test
