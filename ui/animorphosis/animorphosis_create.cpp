// Create > Animorphosis...: the modal that starts the project's animorphosis.
#include <algorithm>
#include <cmath>
#include <vector>

#include <imgui.h>

#include "ui/animorphosis/animorphosis_panel.h"
#include "ui/widgets/create_modal.h"
#include "core/doc/animorphosis_commands.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

constexpr const char* kPopup = "Create Animorphosis##modal";

std::vector<const Actor*> blobActors(const Project& p) {
  std::vector<const Actor*> out;
  for (const Actor& a : p.actors)
    if (a.kind == ActorKind::BlobTree) out.push_back(&a);
  return out;
}

std::string actorLabel(const Actor& a) { return a.name.empty() || a.name == a.id ? a.id : a.name + " (" + a.id + ")"; }

// A combo over the BlobTree actors; returns true when the choice changed.
bool actorCombo(const char* label, const char* key, const std::vector<const Actor*>& actors, std::string& id) {
  const Actor* cur = nullptr;
  for (const Actor* a : actors)
    if (a->id == id) cur = a;
  bool changed = false;
  ImGui::SetNextItemWidth(220.0f);
  if (ImGui::BeginCombo(label, cur ? actorLabel(*cur).c_str() : "(choose)")) {
    for (size_t i = 0; i < actors.size(); ++i) {
      if (ImGui::Selectable(actorLabel(*actors[i]).c_str(), actors[i]->id == id)) {
        id = actors[i]->id;
        changed = true;
      }
      noteWidget(std::string("animorphosis/create/") + key + "/" + std::to_string(i));
    }
    ImGui::EndCombo();
  }
  noteWidget(std::string("animorphosis/create/") + key);
  return changed;
}

}  // namespace

void openCreateAnimorphosis(const Document& doc, CreateAnimorphosisState& st) {
  const Project& p = doc.project();
  const Timeline& tl = p.timeline;
  std::vector<const Actor*> blobs = blobActors(p);
  const AnimorphosisSetup& m = p.animorphosis;
  if (m.enabled()) {
    st.sourceActorId = m.sourceActorId;
    st.targetActorId = m.targetActorId;
    st.startFrame = int(std::lround(tl.secToFrame(m.startSec)));
    st.endFrame = int(std::lround(tl.secToFrame(m.endSec)));
  } else {
    st.sourceActorId = blobs.size() > 0 ? blobs[0]->id : std::string();
    st.targetActorId = blobs.size() > 1 ? blobs[1]->id : std::string();
    const int span = std::max(2, tl.frameEnd - tl.frameStart);
    st.startFrame = tl.frameStart + span / 4;
    st.endFrame = std::max(st.startFrame + 1, tl.frameStart + (3 * span) / 4);
  }
  st.autoMap = true;
  st.error.clear();
  st.openNext = true;
}

void drawCreateAnimorphosisPopup(Document& doc, CreateAnimorphosisState& st, CorrespondenceEditorState& editor,
                                 StatusMessage& status) {
  st.isOpen = beginCentredModal(kPopup, st.openNext);
  if (!st.isOpen) return;
  const Project& p = doc.project();
  std::vector<const Actor*> blobs = blobActors(p);
  bool close = false;
  if (blobs.size() < 2) {
    ImGui::PushTextWrapPos(460.0f);
    ImGui::Text("An animorphosis turns one BlobTree actor into another, and this project has %zu BlobTree actor%s.",
                blobs.size(), blobs.size() == 1 ? "" : "s");
    ImGui::TextDisabled("Create > New BlobTree Actor adds one; animorph-cli animorph SOURCE TARGET -o P.animorph "
                        "makes a project of two BlobTree scenes.");
    ImGui::PopTextWrapPos();
    noteWidget("animorphosis/create/why");
    if (ImGui::Button("Close", ImVec2(110.0f, 0.0f)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
      close = true;
    noteWidget("animorphosis/create/cancel");
  } else {
    ImGui::TextUnformatted("Turn one animated BlobTree into another over an interval of the timeline.");
    if (p.animorphosis.enabled())
      ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.4f, 1.0f), "Replaces the project's animorphosis %s -> %s (undoable).",
                         p.animorphosis.sourceActorId.c_str(), p.animorphosis.targetActorId.c_str());
    if (actorCombo("Source", "source", blobs, st.sourceActorId)) st.error.clear();
    if (actorCombo("Target", "target", blobs, st.targetActorId)) st.error.clear();
    ImGui::SetNextItemWidth(100.0f);
    ImGui::InputInt("Start frame", &st.startFrame, 1, 10);
    noteWidget("animorphosis/create/start");
    ImGui::SetNextItemWidth(100.0f);
    ImGui::InputInt("End frame", &st.endFrame, 1, 10);
    noteWidget("animorphosis/create/end");
    ImGui::Checkbox("Automatic correspondence", &st.autoMap);
    noteWidget("animorphosis/create/auto");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Propose links by node kind, position, size and place in the hierarchy;\n"
                        "off: every part of the source shrinks and every part of the target grows.");
    const ModalChoice choice = createModalButtons(st.error, "animorphosis/create");
    if (choice == ModalChoice::Cancel) close = true;
    if (choice == ModalChoice::Create) {
      const Timeline& tl = p.timeline;
      // Checked without the matching (at once); with it, the editor runs the matching as a job.
      auto cmd = createAnimorphosisCommand(p, st.sourceActorId, st.targetActorId, tl.frameToSec(st.startFrame),
                                           tl.frameToSec(st.endFrame), /*autoMap=*/false);
      if (!cmd) {
        st.error = cmd.error();
        status = {cmd.error(), true};
      } else if (st.autoMap) {
        st.createRequested = true;
        close = true;
      } else {
        std::string label = (*cmd)->label();
        doc.execute(std::move(*cmd));
        const size_t links = doc.project().animorphosis.graph.links.size();
        status = {label + ": " + std::to_string(links) + " link" + (links == 1 ? "" : "s"), false};
        editor.visible = true;
        editor.selected.reset();
        close = true;
      }
    }
  }
  endCreateModal(close, st.isOpen);
}

}  // namespace animorph
