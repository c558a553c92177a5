#include "ui/export/export_dialog.h"

#include <algorithm>
#include <filesystem>

#include <imgui.h>

#include "core/export/export_project.h"
#include "core/export/frame_files.h"
#include "ui/export/export_fields.h"
#include "ui/widgets/create_modal.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {
constexpr const char* kPopup = "Export##modal";

// The default output of a format beside the project: NAME.glb, or the folder NAME_frames.
std::string defaultOutput(const Document& doc, ExportFormat f) {
  const std::string name = framePrefix(doc.project().name);
  return (fs::path(doc.baseDir()) / (f == ExportFormat::GltfAnimated ? name + ".glb" : name + "_frames")).string();
}
}  // namespace

void openExportDialog(const Document& doc, ExportDialogState& st) {
  const ExportSettings& saved = doc.project().exportSettings;
  openSettingsDialog(doc.project(), saved, defaultOutput(doc, saved.format), st);
}

std::string exportSettingsProblem(const Project& p, const ExportSettings& s) {
  int first = 0, last = 0;
  exportFrameRange(p, s, first, last);
  if (s.output.empty()) return "Choose where to write the export (Browse...).";
  if (s.resolution < 2 || s.resolution > 1024) return "The resolution must be 2..1024 cells.";
  return frameRangeProblem(p, first, last, "export");
}

SettingsDialogChoice drawExportDialog(const Document& doc, ExportDialogState& st) {
  st.isOpen = beginCentredModal(kPopup, st.openNext);
  if (!st.isOpen) return SettingsDialogChoice::None;
  SettingsDialogChoice choice = SettingsDialogChoice::None;
  ExportSettings& s = st.edit;
  const Project& p = doc.project();

  ImGui::TextUnformatted("Bake the morph frame by frame and write it out.");
  ImGui::SetNextItemWidth(300.0f);
  if (ImGui::BeginCombo("Format", exportFormatLabel(s.format))) {
    for (int i = 0; i < kExportFormatCount; ++i) {
      const ExportFormat f = ExportFormat(i);
      if (ImGui::Selectable(exportFormatLabel(f), f == s.format) && f != s.format) {
        // The default output follows the format (a .glb file or a folder) until the user picks one.
        const bool wasDefault = s.output == defaultOutput(doc, s.format);
        s.format = f;
        if (wasDefault) s.output = defaultOutput(doc, f);
      }
      noteWidget(std::string("export/format/") + exportFormatName(f));
    }
    ImGui::EndCombo();
  }
  noteWidget("export/format");
  frameRangeFields(p, "export", s.useTimeline, s.first, s.last);
  plainIntField("Resolution", "##resolution", s.resolution);
  s.resolution = std::clamp(s.resolution, 2, 1024);
  noteWidget("export/resolution");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Polygonisation cells along the longest side of the morph's bounds");
  if (outputPathField("export", s.format == ExportFormat::GltfAnimated ? "File" : "Folder", s.output))
    choice = SettingsDialogChoice::Browse;
  if (s.format != ExportFormat::GltfAnimated)
    ImGui::TextDisabled("Frames are written as %s_####.%s in that folder.", framePrefix(p.name).c_str(),
                        exportFormatName(s.format));
  if (s.format == ExportFormat::VdbSequence)
    ImGui::TextDisabled("Level sets of the implicit frames only (B->C); skinned-mesh frames get no file.");
  return finishSettingsDialog(choice, st.error, st.isOpen, "export", "Export", "export",
                              [&] { return exportSettingsProblem(p, s); });
}

}  // namespace animorph
