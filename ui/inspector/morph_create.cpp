#include "ui/inspector/morph_create.h"

#include <imgui.h>

#include <algorithm>
#include <vector>

#include "ui/widgets/create_modal.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

constexpr const char* kPopup = "Create Morph##modal";

std::string actorLabel(const Actor& a) {
  const std::string name = a.name.empty() || a.name == a.id ? a.id : a.name + " (" + a.id + ")";
  return name + (a.kind == ActorKind::BlobTree ? "  [BlobTree]" : "  [glTF]");
}

// A combo over every actor; returns true when the choice changed.
bool actorCombo(const char* label, const std::string& key, const Project& p, std::string& id) {
  const Actor* cur = p.findActor(id);
  bool changed = false;
  ImGui::SetNextItemWidth(240.0f);
  if (ImGui::BeginCombo(label, cur ? actorLabel(*cur).c_str() : "(choose)")) {
    for (size_t i = 0; i < p.actors.size(); ++i) {
      if (ImGui::Selectable(actorLabel(p.actors[i]).c_str(), p.actors[i].id == id)) {
        id = p.actors[i].id;
        changed = true;
      }
      noteWidget(key + "/" + std::to_string(i));
    }
    ImGui::EndCombo();
  }
  noteWidget(key);
  return changed;
}

bool isTree(const Project& p, const std::string& id) {
  const Actor* a = p.findActor(id);
  return a && a->kind == ActorKind::BlobTree;
}

// The target's alignment for the chosen sides, computed once per pair (it poses both characters).
void refreshAlignment(Document& doc, AssetCache& assets, CreateMorphState& st) {
  const std::string key = st.sourceActorId + "\n" + st.targetActorId;
  if (key == st.alignedFor) return;
  st.alignedFor = key;
  st.alignment = proposeTargetAlignment(doc.project(), doc.baseDir(), assets, st.sourceActorId, st.targetActorId);
  st.allowResize = false;
}

// What aligning would do, and the choices: align at all; allow a resize no unit explains.
void drawAlignment(CreateMorphState& st) {
  if (!st.alignment || !st.alignment->alignment.changes()) return;
  const TargetAlignment& a = st.alignment->alignment;
  if (!a.unitNote.empty()) ImGui::TextWrapped("Units: %s.", a.unitNote.c_str());
  ImGui::Checkbox("Align the target to the source", &st.align);
  noteWidget("morph/create/align");
  ImGui::SameLine();
  ImGui::TextDisabled("(scale x%.4g%s)", double(a.transform.scale.x), a.move ? ", onto the source's bounding box" : "");
  if (st.align && a.needsConsent) {
    ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), "%s.", a.sizeNote.c_str());
    ImGui::Checkbox("Allow this resize (the files may be in units they do not declare)", &st.allowResize);
    noteWidget("morph/create/allow_resize");
  }
}

}  // namespace

void openCreateMorph(const Document& doc, CreateMorphState& st) {
  const Project& p = doc.project();
  const MorphSetup& m = p.morph;
  if (m.enabled()) {
    st.sourceActorId = m.sourceActorId;
    st.targetActorId = m.targetActorId;
    st.method = int(m.method);
    const MorphMarkers& k = m.markers;
    st.markers[0] = k.a, st.markers[1] = k.b, st.markers[2] = k.c, st.markers[3] = k.d;
  } else {
    st.sourceActorId = p.actors.size() > 0 ? p.actors[0].id : std::string();
    st.targetActorId = p.actors.size() > 1 ? p.actors[1].id : std::string();
    // Skeleton correspondence when both sides have rigs (glTF characters), else interpolation.
    const bool rigs = !st.sourceActorId.empty() && !st.targetActorId.empty() && !isTree(p, st.sourceActorId) &&
                      !isTree(p, st.targetActorId);
    st.method = int(rigs ? MorphMethod::SkeletonCorrespondence : MorphMethod::Interpolation);
    const Timeline& tl = p.timeline;
    const int span = std::max(8, tl.frameEnd - tl.frameStart);
    for (int i = 0; i < 4; ++i) st.markers[i] = tl.frameStart + span * (i + 1) / 6;
  }
  st.error.clear();
  st.align = true;
  st.alignedFor.clear();
  st.openNext = true;
}

void drawCreateMorphPopup(Document& doc, AssetCache& assets, CreateMorphState& st, StatusMessage& status) {
  st.isOpen = beginCentredModal(kPopup, st.openNext);
  if (!st.isOpen) return;
  const Project& p = doc.project();
  bool close = false;
  ImGui::TextUnformatted("Morph one actor into another: a glTF character or a BlobTree on either side.");
  if (p.morph.enabled())
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.4f, 1.0f), "Replaces the project's morph %s -> %s (undoable).",
                       p.morph.sourceActorId.c_str(), p.morph.targetActorId.c_str());
  if (actorCombo("Source", "morph/create/source", p, st.sourceActorId)) st.error.clear();
  if (actorCombo("Target", "morph/create/target", p, st.targetActorId)) st.error.clear();
  const char* methods[] = {"Interpolation", "Space-time blending", "Skeleton correspondence"};
  ImGui::SetNextItemWidth(240.0f);
  ImGui::Combo("Method", &st.method, methods, 3);
  noteWidget("morph/create/method");
  ImGui::SetNextItemWidth(240.0f);
  ImGui::InputInt4("Markers A B C D", st.markers);
  noteWidget("morph/create/markers");
  const bool treeSource = isTree(p, st.sourceActorId), treeTarget = isTree(p, st.targetActorId);
  if (treeSource || treeTarget)
    ImGui::TextDisabled("A BlobTree is its own stand-in: no %s%s%s (%s).", treeSource ? "collapse" : "",
                        treeSource && treeTarget ? " or " : "", treeTarget ? "expansion" : "",
                        treeSource && treeTarget ? "A = B, C = D" : treeSource ? "A = B" : "C = D");
  refreshAlignment(doc, assets, st);
  drawAlignment(st);
  const ModalChoice choice = createModalButtons(st.error, "morph/create");
  if (choice == ModalChoice::Cancel) close = true;
  if (choice == ModalChoice::Create) {
    MorphChoice c;
    c.sourceActorId = st.sourceActorId;
    c.targetActorId = st.targetActorId;
    c.method = static_cast<MorphMethod>(std::clamp(st.method, 0, 2));
    c.markers = {st.markers[0], st.markers[1], st.markers[2], st.markers[3]};
    std::vector<std::string> notes;
    const bool aligning = st.align && st.alignment && st.alignment->alignment.changes();
    auto m = proposeMorph(p, doc.baseDir(), assets, c, &notes);
    if (m && aligning && st.alignment->alignment.needsConsent && !st.allowResize)
      m = Error{c.targetActorId + ": " + st.alignment->alignment.sizeNote +
                ": tick 'Allow this resize', or untick 'Align the target to the source'"};
    if (!m) {
      st.error = m.error();
      status = {m.error(), true};
    } else {
      const std::string label = "Create morph " + c.sourceActorId + " -> " + c.targetActorId;
      std::optional<Transform> placed;
      if (aligning) placed = st.alignment->targetTransform;
      doc.execute(createMorphCommand(p, std::move(*m), placed, label));
      if (aligning && !st.alignment->alignment.unitNote.empty()) notes.push_back(st.alignment->alignment.unitNote);
      doc.selection = {};
      std::string said;
      for (const std::string& n : notes) said += (said.empty() ? " (" : "; ") + n;
      status = {label + (said.empty() ? std::string() : said + ")"), false};
      close = true;
    }
  }
  endCreateModal(close, st.isOpen);
}

void drawMorphSides(Document& doc, AssetCache& assets, StatusMessage& status) {
  const Project& p = doc.project();
  const MorphSetup& m = p.morph;
  std::string ids[2] = {m.sourceActorId, m.targetActorId};
  bool changed = false;
  changed |= actorCombo("Source", "morph/source", p, ids[0]);
  changed |= actorCombo("Target", "morph/target", p, ids[1]);
  if (changed) {
    MorphChoice c;
    c.sourceActorId = ids[0];
    c.targetActorId = ids[1];
    c.method = m.method;
    c.markers = m.markers;
    auto next = proposeMorph(p, doc.baseDir(), assets, c);
    if (next) doc.execute(setMorphCommand(p, std::move(*next), "Set morph " + ids[0] + " -> " + ids[1]));
    else status = {next.error(), true};
  }
  if (ImGui::Button("Swap source and target")) doc.execute(swapMorphSidesCommand(p));
  noteWidget("morph/swap");
}

}  // namespace animorph
