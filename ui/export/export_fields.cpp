#include "ui/export/export_fields.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include "ui/widgets/widget_rects.h"

namespace animorph {

void plainIntField(const char* label, const char* id, int& v) {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted(label);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80.0f);
  ImGui::InputInt(id, &v, 0, 0);
}

void frameRangeFields(const Project& p, const std::string& prefix, bool& useTimeline, int& first, int& last) {
  if (ImGui::Checkbox("Timeline range", &useTimeline) && useTimeline) {
    first = p.timeline.frameStart;
    last = p.timeline.frameEnd;
  }
  noteWidget(prefix + "/use_timeline");
  ImGui::BeginDisabled(useTimeline);
  plainIntField("First frame", "##first", first);
  noteWidget(prefix + "/first");
  ImGui::SameLine();
  plainIntField("Last frame", "##last", last);
  noteWidget(prefix + "/last");
  ImGui::EndDisabled();
}

std::string frameRangeProblem(const Project& p, int first, int last, const char* what) {
  if (first < 0) return "The first frame must be 0 or later.";
  if (last < first) return "The last frame is before the first.";
  if (!p.morph.enabled() && !p.animorphosis.enabled())
    return std::string("The project has no morph or animorphosis to ") + what +
           " (Create > Animorphosis... makes one).";
  return {};
}

bool outputPathField(const std::string& prefix, const char* label, std::string& output) {
  ImGui::SetNextItemWidth(380.0f);
  ImGui::InputText(label, &output);
  noteWidget(prefix + "/output");
  ImGui::SameLine();
  const bool browse = ImGui::Button("Browse...");
  noteWidget(prefix + "/browse");
  return browse;
}

}  // namespace animorph
