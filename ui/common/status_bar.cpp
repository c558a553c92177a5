#include "ui/common/status_bar.h"

#include <imgui.h>

#include "ui/widgets/widget_rects.h"

namespace animorph {

std::string documentTitle(const Document& doc) { return doc.displayName() + (doc.dirty() ? "*" : ""); }

void drawStatusBar(const LayoutRect& rect, const Document& doc, const FrameStats& stats, const StatusMessage& msg) {
  ImGui::SetNextWindowPos(ImVec2(rect.min.x, rect.min.y));
  ImGui::SetNextWindowSize(ImVec2(rect.size.x, rect.size.y));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8.0f, 2.0f));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));
  constexpr ImGuiWindowFlags kFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                      ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                                      ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoFocusOnAppearing;
  ImGui::SetNextWindowBgAlpha(0.0f);  // the window is cleared to it (EditorUI::windowClearColor)
  ImGui::Begin("##status_bar", nullptr, kFlags);
  ImGui::PopStyleVar(2);
  ImGui::Text("%5.1f fps  %5.2f ms", stats.fps, stats.frameMs);
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  ImGui::TextUnformatted(stats.deviceName.empty() ? "no device" : stats.deviceName.c_str());
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  if (!stats.previewInfo.empty()) {
    ImGui::TextDisabled("%s", stats.previewInfo.c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("|");
    ImGui::SameLine();
  }
  std::string title = documentTitle(doc);
  ImGui::TextUnformatted(title.c_str());
  noteWidget("status/document");
  if (!msg.text.empty()) {
    ImGui::SameLine();
    ImGui::TextDisabled("|");
    ImGui::SameLine();
    if (msg.error) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.35f, 1.0f), "%s", msg.text.c_str());
    else ImGui::TextUnformatted(msg.text.c_str());
    noteWidget("status/message");
  }
  ImGui::End();
}

}  // namespace animorph
