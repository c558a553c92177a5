#include "ui/shell/job_progress_panel.h"

#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "ui/widgets/widget_rects.h"

namespace animorph {

std::string jobProgressText(const BackgroundJob& job) {
  const JobProgress& p = job.progress();
  std::string text = job.label();
  if (std::string stage = p.stage(); !stage.empty()) text += ": " + stage;
  char pct[16];
  std::snprintf(pct, sizeof pct, "  %d%%", int(std::floor(p.fraction() * 100.0)));
  text += pct;
  if (std::string left = formatTimeLeft(p.secondsLeft()); !left.empty()) text += "  about " + left + " left";
  return text;
}

bool drawJobProgressPanel(const LayoutRect& viewport, const BackgroundJob& job) {
  const float width = std::min(520.0f, std::max(200.0f, viewport.size.x - 24.0f));
  ImGui::SetNextWindowPos(ImVec2(viewport.min.x + (viewport.size.x - width) * 0.5f, viewport.max().y - 12.0f),
                          ImGuiCond_Always, ImVec2(0.0f, 1.0f));
  ImGui::SetNextWindowSize(ImVec2(width, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.92f);
  constexpr ImGuiWindowFlags kFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                      ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                      ImGuiWindowFlags_NoNav | ImGuiWindowFlags_AlwaysAutoResize;
  ImGui::Begin("##job_progress", nullptr, kFlags);
  const std::string text = jobProgressText(job);
  ImGui::TextUnformatted(text.c_str());
  const float buttonWidth = 80.0f;
  ImGui::ProgressBar(float(job.progress().fraction()),
                     ImVec2(ImGui::GetContentRegionAvail().x - buttonWidth - ImGui::GetStyle().ItemSpacing.x, 0.0f));
  noteWidget("job/progress");
  ImGui::SameLine();
  const bool cancel = ImGui::Button(job.progress().cancelled() ? "Cancelling" : "Cancel", ImVec2(buttonWidth, 0.0f));
  noteWidget("job/cancel");
  ImGui::End();
  return cancel;
}

}  // namespace animorph
