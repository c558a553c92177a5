#include "ui/widgets/create_modal.h"

#include <imgui.h>

#include "ui/widgets/widget_rects.h"

namespace animorph {

bool beginCentredModal(const char* id, bool& openNext) {
  if (openNext) {
    ImGui::OpenPopup(id);
    openNext = false;
  }
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.4f), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  return ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
}

ModalChoice createModalButtons(const std::string& error, const std::string& keyPrefix, const char* confirm,
                               const char* confirmKey) {
  if (!error.empty()) {
    ImGui::PushTextWrapPos(460.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", error.c_str());
    ImGui::PopTextWrapPos();
    noteWidget(keyPrefix + "/error");
  }
  ImGui::Separator();
  ModalChoice c = ModalChoice::None;
  if (ImGui::Button(confirm, ImVec2(110.0f, 0.0f))) c = ModalChoice::Create;
  noteWidget(keyPrefix + "/" + confirmKey);
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(110.0f, 0.0f)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
    c = ModalChoice::Cancel;
  noteWidget(keyPrefix + "/cancel");
  return c;
}

void endCreateModal(bool close, bool& isOpen) {
  if (close) {
    ImGui::CloseCurrentPopup();
    isOpen = false;
  }
  ImGui::EndPopup();
}

}  // namespace animorph
