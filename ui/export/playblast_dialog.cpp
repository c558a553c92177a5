#include "ui/export/playblast_dialog.h"

#include <algorithm>
#include <filesystem>

#include <imgui.h>

#include "core/export/frame_files.h"
#include "core/export/playblast_job.h"
#include "ui/export/export_fields.h"
#include "ui/widgets/create_modal.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {
constexpr const char* kPopup = "Playblast##modal";
}  // namespace

void openPlayblastDialog(const Document& doc, PlayblastDialogState& st) {
  openSettingsDialog(doc.project(), doc.project().playblastSettings,
                     (fs::path(doc.baseDir()) / (framePrefix(doc.project().name) + ".mp4")).string(), st);
}

std::string playblastSettingsProblem(const Project& p, const PlayblastSettings& s) {
  int first = 0, last = 0;
  playblastFrameRange(p, s, first, last);
  if (s.output.empty()) return "Choose the .mp4 to write (Browse...).";
  if (fs::path(s.output).extension() != ".mp4") return "The playblast is an .mp4 file: end the name with .mp4.";
  if (std::string why = playblastSizeProblem(s); !why.empty()) return why;
  return frameRangeProblem(p, first, last, "playblast");
}

SettingsDialogChoice drawPlayblastDialog(const Document& doc, PlayblastDialogState& st) {
  st.isOpen = beginCentredModal(kPopup, st.openNext);
  if (!st.isOpen) return SettingsDialogChoice::None;
  SettingsDialogChoice choice = SettingsDialogChoice::None;
  PlayblastSettings& s = st.edit;
  const Project& p = doc.project();

  ImGui::TextUnformatted("Bake the morph, draw every frame offscreen and encode an H.264 .mp4 (ffmpeg).");
  frameRangeFields(p, "playblast", s.useTimeline, s.first, s.last);
  plainIntField("Width", "##width", s.width);
  noteWidget("playblast/width");
  ImGui::SameLine();
  plainIntField("Height", "##height", s.height);
  noteWidget("playblast/height");
  s.width = std::clamp(s.width, 16, 8192);
  s.height = std::clamp(s.height, 16, 8192);
  plainIntField("Resolution", "##resolution", s.resolution);
  s.resolution = std::clamp(s.resolution, 2, 1024);
  noteWidget("playblast/resolution");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Polygonisation cells along the longest side of the morph's bounds");
  ImGui::Checkbox("Burn in the frame number and stage", &s.burnIn);
  noteWidget("playblast/burn_in");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("\"frame 0042   B..C\" in the top-left corner of every frame");
  ImGui::Checkbox("Viewport camera", &s.viewportCamera);
  noteWidget("playblast/viewport_camera");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Seen as in the viewport now; off: one camera that frames every frame of the range");
  if (outputPathField("playblast", "File", s.output)) choice = SettingsDialogChoice::Browse;
  ImGui::TextDisabled("%g frames/s (the timeline's).", p.timeline.fps);
  return finishSettingsDialog(choice, st.error, st.isOpen, "playblast", "Playblast", "start",
                              [&] { return playblastSettingsProblem(p, s); });
}

}  // namespace animorph
