#pragma once
// Begins a modal dialog centred near the top of the display (its own size), opening it first when
// openNext is set (which it clears). Returns true while it is open: draw its contents, then
// ImGui::EndPopup().
#include <imgui.h>

namespace animorph {

inline bool beginCentredModal(const char* id, bool& openNext) {
  if (openNext) {
    ImGui::OpenPopup(id);
    openNext = false;
  }
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.4f), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  return ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
}

}  // namespace animorph
