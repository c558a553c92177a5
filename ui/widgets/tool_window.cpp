#include "ui/widgets/tool_window.h"

#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

bool beginWindow(const char* title, const std::string& widgetKey, ToolWindowFlags f, ImGuiWindowFlags flags) {
  bool open = true;
  if (!ImGui::Begin(title, &open, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings | flags)) {
    ImGui::End();
    f.visible = open;
    return false;
  }
  f.visible = open;
  if (!open) f.placeNext = true;
  f.focused = ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows);
  const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  noteWidgetRect(widgetKey, {p.x, p.y}, {p.x + s.x, p.y + s.y});
  return true;
}

}  // namespace

bool beginToolWindow(const char* title, ImVec2 pos, ImVec2 size, const std::string& widgetKey, ToolWindowFlags f) {
  f.focused = false;
  if (!f.visible) return false;
  if (f.placeNext) {
    ImGui::SetNextWindowPos(pos);
    ImGui::SetNextWindowSize(size);
    f.placeNext = false;
  }
  return beginWindow(title, widgetKey, f, 0);
}

bool beginDockedToolWindow(const char* title, ImVec2 pos, ImVec2 size, const std::string& widgetKey,
                           ToolWindowFlags f) {
  f.focused = false;
  if (!f.visible || size.x <= 0.0f || size.y <= 0.0f) return false;
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  return beginWindow(title, widgetKey, f, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
}

}  // namespace animorph
