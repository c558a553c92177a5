#include "ui/inspector/standin_inspector.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "ui/common/command_result.h"
#include "core/doc/standin_commands.h"
#include "core/scene/standin_guides.h"
#include "core/standin/character_pose.h"
#include "core/standin/fit_standin.h"
#include "core/standin/standin_edit.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

std::string nodeName(const Character& c, int node) {
  if (node < 0 || node >= int(c.nodes.size())) return "node " + std::to_string(node) + " (missing)";
  const std::string& n = c.nodes[size_t(node)].name;
  return n.empty() ? "node " + std::to_string(node) : n;
}

FitSettings fitSettingsFor(const Standin& s) {
  FitSettings fs;
  fs.kind = s.kind;
  fs.measure = false;
  return fs;
}

bool run(Document& doc, Result<std::unique_ptr<Command>> cmd, StatusMessage& status) {
  return executeOrReport(doc, std::move(cmd), status, true);
}

void insertAndSelect(Document& doc, const std::string& actorId, int at, const StandinSegment& seg, std::string label,
                     StandinToolState& st, StatusMessage& status) {
  if (!run(doc, insertStandinSegmentCommand(doc.project(), actorId, at, seg, std::move(label)), status)) return;
  st.part = StandinPart::Whole;
  doc.selection = Selection{actorId, -1, at};
}

}  // namespace

StandinSegment newSegmentOnNode(const Character& c, const Standin& s, int node) {
  StandinSegment seg;
  seg.node = node;
  std::vector<float> radii;
  for (const auto& x : s.segments) radii.push_back(x.radius);
  if (!radii.empty()) {
    std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
    seg.radius = radii[radii.size() / 2];
  }
  const auto rig = rigNodes(c);
  seg.b = glm::vec3(0.0f, 3.0f * seg.radius, 0.0f);
  if (node >= 0 && node < int(c.nodes.size()))
    for (int child : c.nodes[size_t(node)].children)
      if (child >= 0 && child < int(rig.size()) && rig[size_t(child)] &&
          glm::length(c.nodes[size_t(child)].rest.translation) > kMinSegmentLength) {
        seg.b = c.nodes[size_t(child)].rest.translation;
        break;
      }
  return seg;
}

void drawJointStandinButton(Document& doc, const Character& c, const std::string& actorId, int node,
                            StandinToolState& st, StatusMessage& status) {
  const ActorMorph* am = doc.project().morph.findActor(actorId);
  if (!am) return;
  ImGui::Separator();
  if (ImGui::Button("Add stand-in segment on this joint")) {
    const int at = int(am->standin.segments.size());
    insertAndSelect(doc, actorId, at, newSegmentOnNode(c, am->standin, node),
                    "Add stand-in segment on " + nodeName(c, node), st, status);
  }
  noteWidget("inspector/standin/add_on_joint");
}

namespace {

// Radii are shown in scene units (the joint's and the actor's scales applied, as the viewport
// draws them); segment ends stay in the joint's space.
struct SceneScale {
  const Actor* actor = nullptr;
  std::vector<glm::mat4> globals;  // the actor's pose at the document's time
  float operator()(int node) const {
    if (!actor || node < 0 || node >= int(globals.size())) return 1.0f;
    const float k = radiusScale(actor->transform.matrix() * globals[size_t(node)]);
    return k > 0.0f ? k : 1.0f;
  }
};

// The list: index, joint, radius; a click selects a segment. Returns the selected one (-1: none).
int drawSegmentList(Document& doc, const Character& c, const std::string& actorId, const Standin& standin,
                    const SceneScale& sceneScale, int sel, StandinToolState& st) {
  const float rows = float(std::min<size_t>(standin.segments.size(), 8));
  if (ImGui::BeginChild("##standin_segments", ImVec2(0.0f, ImGui::GetTextLineHeightWithSpacing() * (rows + 0.5f)),
                        true)) {
    for (int i = 0; i < int(standin.segments.size()); ++i) {
      const StandinSegment& s = standin.segments[size_t(i)];
      char label[160];
      std::snprintf(label, sizeof label, "%2d  %-18s r %.4g m##seg%d", i, nodeName(c, s.node).c_str(),
                    double(s.radius * sceneScale(s.node)), i);
      if (ImGui::Selectable(label, i == sel)) {
        st.part = StandinPart::Whole;
        doc.selection = Selection{actorId, -1, i};
        sel = i;
      }
      noteWidget("inspector/standin/segment/" + std::to_string(i));
      if (i == sel && st.scrollList) {
        ImGui::SetScrollHereY();
        st.scrollList = false;
      }
    }
  }
  ImGui::EndChild();
  return sel;
}

// Structure edits: Add, Duplicate, Delete, Refit (the selected segment) and Refit all (a job).
void drawSegmentButtons(Document& doc, const Character& c, const std::string& actorId, const Standin& standin, int sel,
                        StandinToolState& st, StatusMessage& status) {
  const int addNode = sel >= 0 ? standin.segments[size_t(sel)].node
                               : (standin.segments.empty() ? -1 : standin.segments.front().node);
  if (ImGui::Button("Add") && addNode >= 0)
    insertAndSelect(doc, actorId, int(standin.segments.size()), newSegmentOnNode(c, standin, addNode),
                    "Add stand-in segment on " + nodeName(c, addNode), st, status);
  noteWidget("inspector/standin/add");
  ImGui::SameLine();
  ImGui::BeginDisabled(sel < 0);
  if (ImGui::Button("Duplicate") && sel >= 0)
    insertAndSelect(doc, actorId, sel + 1, standin.segments[size_t(sel)],
                    "Duplicate stand-in segment " + std::to_string(sel), st, status);
  noteWidget("inspector/standin/duplicate");
  ImGui::SameLine();
  if (ImGui::Button("Delete") && sel >= 0 && run(doc, deleteStandinSegmentCommand(doc.project(), actorId, sel), status))
    doc.selection.segment = std::min(sel, int(standin.segments.size()) - 2);
  noteWidget("inspector/standin/delete");
  ImGui::SameLine();
  if (ImGui::Button("Refit") && sel >= 0) {
    auto fitted = refitSegment(c, standin.segments[size_t(sel)], fitSettingsFor(standin));
    if (!fitted) status = {"Refit segment " + std::to_string(sel) + ": " + fitted.error(), true};
    else
      run(doc, setStandinSegmentCommand(doc.project(), actorId, sel, *fitted, "Refit stand-in segment " + std::to_string(sel)),
          status);
  }
  noteWidget("inspector/standin/refit");
  ImGui::EndDisabled();
  ImGui::SameLine();
  // The whole fit (and its report) takes up to a second on a large character: a background job.
  if (ImGui::Button("Refit all")) st.refitAllRequest = actorId;
  noteWidget("inspector/standin/refit_all");
}

// Rebind: the segment keeps its place at the current frame.
void drawSegmentJoint(Document& doc, const Character& c, const std::string& actorId, int sel,
                      const StandinSegment& seg, StatusMessage& status) {
  if (ImGui::BeginCombo("Joint", nodeName(c, seg.node).c_str())) {
    const auto rig = rigNodes(c);
    for (int n = 0; n < int(rig.size()); ++n) {
      if (!rig[size_t(n)]) continue;
      const bool picked = ImGui::Selectable(nodeName(c, n).c_str(), n == seg.node);
      noteWidget("inspector/standin/joint/" + nodeName(c, n));
      if (picked && n != seg.node) {
        const Actor* actor = doc.project().findActor(actorId);
        const auto globals = actorPoseGlobals(*actor, c, documentTimeSec(doc));
        run(doc, setStandinSegmentCommand(doc.project(), actorId, sel, rebindSegment(seg, n, globals),
                                          "Rebind stand-in segment " + std::to_string(sel) + " to " + nodeName(c, n)),
            status);
      }
    }
    ImGui::EndCombo();
  }
  noteWidget("inspector/standin/joint");
}

// The selected segment's radius (scene units) and ends (the joint's space); each drag one command.
void drawSegmentShape(Document& doc, const std::string& actorId, int sel, const StandinSegment& seg, float scale,
                      DragMerge& drag, StatusMessage& status) {
  const std::string key = actorId + "/" + std::to_string(sel);
  float radius = seg.radius * scale;
  bool changed = ImGui::DragFloat("Radius", &radius, 0.001f * scale, 1e-4f * scale, 100.0f * scale, "%.4g m (scene)");
  noteWidget("inspector/standin/radius");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("In scene units (glTF metres, every node and actor scale applied); x%.4g of the joint's own units",
                      double(scale));
  drag.begin(doc);
  if (changed && radius > 0.0f) {
    StandinSegment next = seg;
    next.radius = radius / scale;
    run(doc, setStandinSegmentCommand(doc.project(), actorId, sel, next, "Stand-in radius", "standin/radius/" + key),
        status);
  }
  drag.end(doc);
  for (int end = 0; end < 2; ++end) {
    glm::vec3 v = end == 0 ? seg.a : seg.b;
    changed = ImGui::DragFloat3(end == 0 ? "End A" : "End B", &v.x, 0.002f, 0.0f, 0.0f, "%.3f");
    noteWidget(end == 0 ? "inspector/standin/a" : "inspector/standin/b");
    drag.begin(doc);
    if (changed) {
      StandinSegment next = seg;
      (end == 0 ? next.a : next.b) = v;
      run(doc, setStandinSegmentCommand(doc.project(), actorId, sel, next, "Move stand-in segment",
                                        "standin/move/" + key),
          status);
    }
    drag.end(doc);
  }
}

}  // namespace

void drawStandinInspector(Document& doc, const Character& c, const std::string& actorId, StandinToolState& st,
                          DragMerge& drag, StatusMessage& status) {
  const ActorMorph* found = doc.project().morph.findActor(actorId);
  if (!found) return;
  const Standin standin = found->standin;  // copy: commands below change the project
  ImGui::Separator();
  if (!ImGui::CollapsingHeader("Stand-in", ImGuiTreeNodeFlags_DefaultOpen)) return;
  noteWidget("inspector/standin");
  ImGui::TextDisabled("%zu segments (%s)", standin.segments.size(), standinKindName(standin.kind));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("View > Stand-in Edit Mode (E) edits them in the viewport");
  int sel = selectedStandinSegment(doc);
  if (doc.selection.actorId != actorId) sel = -1;
  SceneScale sceneScale;
  sceneScale.actor = doc.project().findActor(actorId);
  if (sceneScale.actor) sceneScale.globals = actorPoseGlobals(*sceneScale.actor, c, documentTimeSec(doc));

  sel = drawSegmentList(doc, c, actorId, standin, sceneScale, sel, st);
  drawSegmentButtons(doc, c, actorId, standin, sel, st, status);
  if (sel < 0 || sel >= int(doc.project().morph.findActor(actorId)->standin.segments.size())) return;
  const StandinSegment seg = doc.project().morph.findActor(actorId)->standin.segments[size_t(sel)];
  ImGui::PushItemWidth(-90.0f);
  drawSegmentJoint(doc, c, actorId, sel, seg, status);
  const float scale = sceneScale(seg.node);
  drawSegmentShape(doc, actorId, sel, seg, scale, drag, status);
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("Ends in the joint's space; radius in scene units (x%.4g of the joint's).", double(scale));
  ImGui::PopTextWrapPos();
  ImGui::PopItemWidth();
}

}  // namespace animorph
