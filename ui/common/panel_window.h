#pragma once
// A docked panel's window (the outliner, the inspector, the timeline): placed on its layout
// rectangle each frame, not movable, resizable or collapsible, no saved settings, never brought in
// front of the floating tools, and transparent (the editor clears the window to the panel colour,
// EditorUI::windowClearColor).
#include <imgui.h>

#include "ui/common/layout.h"

namespace animorph {

// Begins the panel's window on rect with extraFlags added to the docked ones. Returns true when
// its contents are to be drawn (call ImGui::End() after them); false when there is nothing to draw
// (the window is already ended).
inline bool beginPanelWindow(const char* title, const LayoutRect& rect, ImGuiWindowFlags extraFlags = 0) {
  ImGui::SetNextWindowPos(ImVec2(rect.min.x, rect.min.y));
  ImGui::SetNextWindowSize(ImVec2(rect.size.x, rect.size.y));
  constexpr ImGuiWindowFlags kDocked = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                       ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
                                       ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::SetNextWindowBgAlpha(0.0f);
  if (!ImGui::Begin(title, nullptr, kDocked | extraFlags)) {
    ImGui::End();
    return false;
  }
  return true;
}

}  // namespace animorph
