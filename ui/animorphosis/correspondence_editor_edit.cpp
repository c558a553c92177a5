// The correspondence editor's edits: every change as an undoable command (correspondence_editor_intern.h).
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "core/doc/animorphosis_commands.h"
#include "ui/animorphosis/correspondence_editor_intern.h"
#include "ui/common/command_result.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

void runCorrCommand(Document& doc, Result<std::unique_ptr<Command>> cmd, StatusMessage& status, std::string note) {
  if (executeOrReport(doc, std::move(cmd), status, /*announce=*/true)) status.text += note;
}

AutoCorrespondSettings autoMapSettings(const Project& p) {
  const AnimorphosisTiming t = animorphosisTiming(p);
  AutoCorrespondSettings settings;
  settings.timeSecA = t.source.localTime(t.startSec);
  settings.timeSecB = t.target.localTime(t.startSec);
  return settings;
}

std::string autoMapNote(const AutoCorrespondReport& report) {
  char buf[160];
  std::snprintf(buf, sizeof buf, ": %d proposed (mean confidence %.2f), %d suggested, %d artist link%s kept",
                report.proposed, report.meanConfidence, report.suggested, report.artistKept,
                report.artistKept == 1 ? "" : "s");
  return buf;
}

void dropCorrWire(CorrFrame& f) {
  CorrespondenceEditorState& st = f.st;
  if (st.dragSide < 0 || ImGui::IsMouseDown(0)) return;
  const bool fromA = st.dragSide == 0;
  const CorrTreeRows& to = fromA ? f.rb : f.ra;
  const glm::vec2 mouse = f.mouse;
  int hit = -1;
  for (const CorrRow& r : to.rows)
    if (mouse.x >= r.min.x && mouse.x < r.max.x && mouse.y >= r.min.y && mouse.y < r.max.y) hit = r.node->id;
  if (hit >= 0) {
    const int nodeA = fromA ? st.dragNode : hit, nodeB = fromA ? hit : st.dragNode;
    auto cmd = addCorrespondenceLinkCommand(f.doc.project(), nodeA, nodeB);
    if (cmd) st.selected = CorrespondenceLinkRef{nodeA, nodeB};
    runCorrCommand(f.doc, std::move(cmd), f.status);
  }
  st.dragSide = -1;
  st.dragNode = -1;
}

void drawCorrSuggestionMenu(CorrFrame& f) {
  CorrespondenceEditorState& st = f.st;
  if (!ImGui::BeginPopup("##suggestion_menu")) return;
  if (st.selectedSuggestion && ImGui::MenuItem("Accept")) {
    runCorrCommand(f.doc,
                   acceptSuggestionCommand(f.doc.project(), st.selectedSuggestion->nodeA, st.selectedSuggestion->nodeB),
                   f.status);
    st.selectedSuggestion.reset();
  }
  noteWidget("corr/menu/accept");
  ImGui::EndPopup();
}

void drawCorrWireMenu(CorrFrame& f) {
  CorrespondenceEditorState& st = f.st;
  if (!ImGui::BeginPopup("##wire_menu")) return;
  if (st.selected) {
    const CorrespondenceGraph& graph = f.setup.graph;
    const int i = graph.find(st.selected->nodeA, st.selected->nodeB);
    if (ImGui::MenuItem("Cut")) {
      runCorrCommand(f.doc, removeCorrespondenceLinkCommand(f.doc.project(), st.selected->nodeA, st.selected->nodeB),
                     f.status);
      st.selected.reset();
    }
    noteWidget("corr/menu/cut");
    if (i >= 0 && !graph.links[size_t(i)].sOverride && ImGui::MenuItem("Own s(u)"))
      runCorrCommand(f.doc,
                     setLinkSOverrideCommand(f.doc.project(), st.selected->nodeA, st.selected->nodeB, f.setup.globalS),
                     f.status);
    if (i >= 0 && graph.links[size_t(i)].sOverride && ImGui::MenuItem("Inherit s(u)"))
      runCorrCommand(f.doc,
                     setLinkSOverrideCommand(f.doc.project(), st.selected->nodeA, st.selected->nodeB, std::nullopt),
                     f.status);
  }
  ImGui::EndPopup();
}

namespace {

// Removes the links the knife's trail crossed, as one command (refused when the graph would break a rule).
void cutCrossedLinks(CorrFrame& f) {
  CorrespondenceEditorState& st = f.st;
  std::vector<CorrespondenceLinkRef> cut;
  for (const CorrWire& w : f.wires)
    if (corrWireCrossesTrail(w, st.cutTrail))
      cut.push_back({f.setup.graph.links[size_t(w.link)].nodeA, f.setup.graph.links[size_t(w.link)].nodeB});
  st.cutTrail.clear();
  if (cut.empty()) return;
  Document& doc = f.doc;
  AnimorphosisSetup after = doc.project().animorphosis;
  for (const CorrespondenceLinkRef& c : cut) {
    int i = after.graph.find(c.nodeA, c.nodeB);
    if (i >= 0) after.graph.links.erase(after.graph.links.begin() + i);
  }
  Project trial = doc.project();
  trial.animorphosis = after;
  if (Status s = checkAnimorphosis(trial); !s) {
    f.status = {s.error(), true};
  } else {
    const std::string label = "Cut " + std::to_string(cut.size()) + " link" + (cut.size() == 1 ? "" : "s");
    doc.execute(setAnimorphosisCommand(doc.project(), std::move(after), label));
    f.status = {label, false};
    st.selected.reset();
  }
}

}  // namespace

void cutCorrWiresWithKnife(CorrFrame& f) {
  CorrespondenceEditorState& st = f.st;
  if (f.graphHovered && ImGui::GetIO().KeyCtrl && ImGui::IsMouseClicked(1)) st.cutTrail = {f.mouse};
  if (st.cutTrail.empty()) return;
  if (ImGui::IsMouseDown(1)) {
    if (glm::length(f.mouse - st.cutTrail.back()) > 3.0f) st.cutTrail.push_back(f.mouse);
    drawCorrKnifeTrail(f);
  } else {
    cutCrossedLinks(f);
  }
}

void deleteSelectedCorrLink(Document& doc, CorrespondenceEditorState& st, StatusMessage& status) {
  if (st.focused && st.selected && !ImGui::GetIO().WantTextInput &&
      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false)) {
    runCorrCommand(doc, removeCorrespondenceLinkCommand(doc.project(), st.selected->nodeA, st.selected->nodeB), status);
    st.selected.reset();
  }
}

}  // namespace animorph
