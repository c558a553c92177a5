#include "ui/shell/help_windows.h"

#include <imgui.h>

#include "ui/common/shortcuts.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

void drawShortcutsWindow(bool& open) {
  if (!open) return;
  ImGui::SetNextWindowSize(ImVec2(440.0f, 480.0f), ImGuiCond_Appearing);
  if (!ImGui::Begin("Shortcuts", &open, ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return;
  }
  if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
    ImGui::TableSetupColumn("Keys", ImGuiTableColumnFlags_WidthFixed, 130.0f);
    ImGui::TableSetupColumn("Action");
    ImGui::TableHeadersRow();
    for (const Shortcut& s : shortcutTable()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(shortcutText(s).c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(s.description);
    }
    ImGui::EndTable();
  }
  noteWidget("shortcuts/table");
  ImGui::Spacing();
  ImGui::TextUnformatted("Viewport (Maya scheme)");
  ImGui::BulletText("Alt + left drag: orbit");
  ImGui::BulletText("Alt + middle drag: pan");
  ImGui::BulletText("Alt + right drag: dolly");
  ImGui::TextUnformatted("Viewport (Blender scheme)");
  ImGui::BulletText("Middle drag: orbit");
  ImGui::BulletText("Shift + middle drag: pan");
  ImGui::BulletText("Ctrl + middle drag: dolly");
  ImGui::TextUnformatted("Both");
  ImGui::BulletText("Wheel: zoom");
  ImGui::BulletText("Left click: select (pick)");
  ImGui::BulletText("F: frame the selection");
  ImGui::TextUnformatted("Timeline");
  ImGui::BulletText("Click or drag on the ruler: scrub");
  ImGui::BulletText("Wheel on the ruler: zoom, middle drag: pan, middle double-click: fit range");
  ImGui::End();
}

void drawAboutWindow(bool& open) {
  if (!open) return;
  if (!ImGui::Begin("About Animorph", &open,
                    ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return;
  }
  ImGui::TextUnformatted("Animorph");
  ImGui::TextUnformatted("Metamorphosis between animated 3D characters of any topology.");
  ImGui::Separator();
  ImGui::Text("Dear ImGui %s", ImGui::GetVersion());
  ImGui::End();
}

}  // namespace animorph
