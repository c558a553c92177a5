// EditorUI's look: the window's clear colour and the ImGui style.
#include "ui/shell/editor_ui.h"

#include <imgui.h>

namespace animorph {

void EditorUI::windowClearColor(float rgba[4]) {
  const ImVec4 c = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  rgba[0] = c.x;
  rgba[1] = c.y;
  rgba[2] = c.z;
  rgba[3] = 1.0f;
}

void EditorUI::applyStyle() {
  ImGuiStyle& s = ImGui::GetStyle();
  ImGui::StyleColorsDark(&s);
  s.WindowRounding = 0.0f;
  s.FrameRounding = 3.0f;
  s.GrabRounding = 3.0f;
  s.WindowBorderSize = 1.0f;
  s.ItemSpacing = ImVec2(6.0f, 4.0f);
  s.Colors[ImGuiCol_WindowBg] = ImVec4(0.16f, 0.16f, 0.18f, 1.0f);
  s.Colors[ImGuiCol_TitleBgActive] = ImVec4(0.20f, 0.22f, 0.27f, 1.0f);
}

}  // namespace animorph
