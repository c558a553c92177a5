#include "ui/shell/preferences_window.h"

#include <imgui.h>

#include "ui/shell/preview_controls.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

bool drawPreferencesWindow(bool& open, Preferences& prefs, const std::string& prefsPath) {
  if (!open) return false;
  bool changed = false;
  ImGui::SetNextWindowSize(ImVec2(460.0f, 0.0f), ImGuiCond_Appearing);
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.35f), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Preferences", &open, ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return false;
  }
  ImGui::TextUnformatted("Viewport camera");
  int scheme = prefs.cameraScheme == CameraScheme::Maya ? 0 : 1;
  const char* schemes[] = {"Maya (Alt + mouse buttons)", "Blender (middle mouse button)"};
  if (ImGui::Combo("Scheme", &scheme, schemes, 2)) {
    prefs.cameraScheme = scheme == 0 ? CameraScheme::Maya : CameraScheme::Blender;
    changed = true;
  }
  noteWidget("prefs/scheme");
  if (ImGui::Checkbox("Also accept the other scheme's bindings", &prefs.otherSchemeToo)) changed = true;
  noteWidget("prefs/other_scheme");

  ImGui::Separator();
  ImGui::TextUnformatted("Autosave");
  float interval = static_cast<float>(prefs.autosaveIntervalSec);
  ImGui::SliderFloat("Interval (s)", &interval, 0.0f, 600.0f, interval <= 0.0f ? "off" : "%.0f s");
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    prefs.autosaveIntervalSec = interval < 1.0f ? 0.0 : interval;
    changed = true;
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Implicit preview (BlobTrees, the morph's B-C stage)");
  if (drawPreviewSettings(prefs)) changed = true;

  ImGui::Separator();
  ImGui::TextUnformatted("Layout");
  ImGui::DragFloat("Outliner width", &prefs.outlinerWidth, 1.0f, 0.0f, 5000.0f, "%.0f px");
  if (ImGui::IsItemDeactivatedAfterEdit()) changed = true;
  ImGui::DragFloat("Inspector width", &prefs.inspectorWidth, 1.0f, 0.0f, 5000.0f, "%.0f px");
  if (ImGui::IsItemDeactivatedAfterEdit()) changed = true;
  ImGui::DragFloat("Timeline height", &prefs.timelineHeight, 1.0f, 0.0f, 5000.0f, "%.0f px");
  if (ImGui::IsItemDeactivatedAfterEdit()) changed = true;
  ImGui::DragFloat("Docked editors height", &prefs.editorsHeight, 1.0f, 0.0f, 5000.0f, "%.0f px");
  if (ImGui::IsItemDeactivatedAfterEdit()) changed = true;
  if (ImGui::Button("Reset layout")) {
    Preferences d;
    prefs.outlinerWidth = d.outlinerWidth;
    prefs.inspectorWidth = d.inspectorWidth;
    prefs.timelineHeight = d.timelineHeight;
    prefs.editorsHeight = d.editorsHeight;
    prefs.editorsSplit = d.editorsSplit;
    changed = true;
  }

  ImGui::Separator();
  ImGui::Text("Recent files: %zu", prefs.recentFiles.size());
  ImGui::SameLine();
  if (ImGui::Button("Clear")) {
    prefs.recentFiles.clear();
    changed = true;
  }
  ImGui::TextDisabled("Saved in %s", prefsPath.c_str());
  ImGui::End();
  return changed;
}

}  // namespace animorph
