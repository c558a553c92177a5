// The morph panel's projection section: how vertices are bound to the
// stand-ins (pose, limits) and pulled back near alpha = 1, and the report of
// the prepared morph. A change re-prepares the morph (the viewport's morph is
// cached per document revision), so the report follows within a frame or two.
#include <cstdio>

#include <imgui.h>

#include "ui/inspector/morph_sections.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

std::unique_ptr<Command> setProjection(const Project& p, const MorphProjection& next, std::string mergeKey = {}) {
  return std::make_unique<SetValueCommand<MorphProjection>>(
      "Set morph projection", [](Project& proj) { return &proj.morph.projection; }, p.morph.projection, next,
      std::move(mergeKey));
}

void reportActor(const char* role, const MorphActorRuntime& a) {
  if (a.isTree()) {
    ImGui::Text("%s '%s': a BlobTree, its own stand-in (nothing projected)", role, a.actor.id.c_str());
    noteWidget(std::string("morph/report/") + role);
    return;
  }
  const ProjectionStats& s = a.binding.stats;
  ImGui::Text("%s '%s': %zu vertices", role, a.actor.id.c_str(), s.points);
  ImGui::Text("  converged %zu, fallbacks %zu, failures %zu", s.converged, s.fallbacks, s.failures);
  noteWidget(std::string("morph/report/") + role);
  ImGui::Text("  max |f| %.2g, mean move %.3g m, %.0f ms", double(s.maxAbsField), s.meanDistance, s.milliseconds);
}

}  // namespace

void drawMorphProjection(Document& doc, const MorphPanelState& st, DragMerge& drag) {
  const bool open = ImGui::CollapsingHeader("Projection");
  noteWidget("morph/projection");
  if (!open) return;
  const MorphProjection pr = doc.project().morph.projection;
  MorphProjection next = pr;
  ImGui::PushItemWidth(-110.0f);
  int pose = pr.atClipTime ? 1 : 0;
  const char* poses[] = {"Rest pose", "Clip at a time"};
  if (ImGui::Combo("Pose", &pose, poses, 2)) {
    next.atClipTime = pose == 1;
    doc.execute(setProjection(doc.project(), next));
  }
  noteWidget("morph/projection/pose");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The pose each actor is projected onto its stand-in in");
  // A drag field: one command per change, merged while the mouse is down.
  auto field = [&](bool changed, const char* key) {
    noteWidget(std::string("morph/projection/") + key);
    drag.begin(doc);
    if (changed && !(next == pr)) doc.execute(setProjection(doc.project(), next, std::string("morph/projection/") + key));
    drag.end(doc);
  };
  if (pr.atClipTime) {
    float t = float(next.clipTimeSec);
    bool c = ImGui::DragFloat("Clip time (s)", &t, 0.01f, 0.0f, 1000.0f, "%.3f");
    next.clipTimeSec = std::max(0.0f, t);
    field(c, "clip_time");
  }
  bool c = ImGui::DragInt("Iterations", &next.maxIterations, 0.2f, 1, 500);
  next.maxIterations = std::clamp(next.maxIterations, 1, 500);
  field(c, "iterations");
  c = ImGui::DragFloat("Tolerance", &next.tolerance, 1e-6f, 1e-8f, 1e-2f, "%.1e", ImGuiSliderFlags_Logarithmic);
  next.tolerance = std::clamp(next.tolerance, 1e-8f, 1e-2f);
  field(c, "tolerance");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("|f| below which a vertex counts as on the stand-in");
  c = ImGui::DragFloat("Step (radii)", &next.maxStepRadii, 0.01f, 0.05f, 2.0f, "%.2f");
  next.maxStepRadii = std::clamp(next.maxStepRadii, 0.05f, 2.0f);
  field(c, "step");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Longest Newton step, in segment radii");
  c = ImGui::SliderFloat("Reproject from", &next.reprojectFrom, 0.0f, 1.0f, "%.2f");
  field(c, "reproject_from");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("alpha from which vertices are pulled onto the posed stand-in (1: never)");
  ImGui::PopItemWidth();

  // Report of the prepared morph.
  ImGui::Separator();
  const MorphRuntime* rt = st.runtime.get();
  if (!rt) {
    ImGui::TextDisabled("No projection report (the morph is not prepared).");
    return;
  }
  if (!(rt->setup.projection == doc.project().morph.projection)) ImGui::TextDisabled("Projecting again...");
  reportActor("source", rt->source);
  reportActor("target", rt->target);
  for (const std::string& n : rt->notes) ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s", n.c_str());
}

}  // namespace animorph
