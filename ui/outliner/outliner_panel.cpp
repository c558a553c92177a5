#include "ui/outliner/outliner_panel.h"

#include "ui/common/panel_window.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/doc/actor_commands.h"
#include "editor/selection_info.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {
namespace {

const ImVec4 kErrorColor{1.0f, 0.4f, 0.35f, 1.0f};
constexpr int kMaxDepth = 256;  // import rejects cycles; this guards against deep garbage

const char* nodeKind(const Character& c, int node, const std::vector<char>& isJoint) {
  if (c.nodes[node].mesh >= 0) return c.nodes[node].skin >= 0 ? "skinned mesh" : "mesh";
  if (isJoint[node]) return "joint";
  return "node";
}

void drawNode(const Character& c, int node, const std::vector<char>& isJoint, const Actor& actor, Document& doc,
              int depth) {
  if (node < 0 || node >= static_cast<int>(c.nodes.size()) || depth > kMaxDepth) return;
  const Node& n = c.nodes[node];
  ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_OpenOnDoubleClick |
                             ImGuiTreeNodeFlags_SpanAvailWidth;
  if (n.children.empty()) flags |= ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen;
  if (doc.selection.actorId == actor.id && doc.selection.node == node) flags |= ImGuiTreeNodeFlags_Selected;
  std::string label = (n.name.empty() ? "node " + std::to_string(node) : n.name) + "  (" +
                      nodeKind(c, node, isJoint) + ")";
  ImGui::PushID(node);
  bool open = ImGui::TreeNodeEx("##node", flags, "%s", label.c_str());
  noteWidget("outliner/" + actor.id + "/node/" + std::to_string(node));
  if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) doc.selection = {actor.id, node};
  if (open && !n.children.empty()) {
    for (int child : n.children) drawNode(c, child, isJoint, actor, doc, depth + 1);
    ImGui::TreePop();
  }
  ImGui::PopID();
}

}  // namespace

void beginRename(OutlinerState& st, const Document& doc, const std::string& actorId) {
  const Actor* a = doc.project().findActor(actorId);
  if (!a) return;
  st.renamingActorId = actorId;
  st.renameBuffer = a->name;
  st.focusRename = true;
}

void drawOutlinerPanel(const LayoutRect& rect, Document& doc, AssetCache& assets, OutlinerState& st,
                       std::vector<Action>& actions, StatusMessage& status) {
  if (!beginPanelWindow("Outliner", rect)) return;
  if (ImGui::SmallButton("+ Import")) actions.push_back(Action::ImportCharacter);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Import a character: glTF, FBX, Collada or OBJ");
  noteWidget("outliner/import");
  ImGui::SameLine();
  if (ImGui::SmallButton("+ BlobTree")) actions.push_back(Action::NewBlobActor);
  noteWidget("outliner/new_blob");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("New BlobTree actor (a blend of one sphere)");
  ImGui::Separator();

  const Project& project = doc.project();
  if (project.actors.empty())
    ImGui::TextWrapped("No actors. File > Import Character... adds a character; Create > New BlobTree Actor an implicit "
                       "shape.");
  std::string deleteId;
  // Copy: a command executed below may reallocate project.actors.
  std::vector<Actor> actors = project.actors;
  for (const Actor& actor : actors) {
    ImGui::PushID(actor.id.c_str());
    bool visible = actor.visible;
    if (ImGui::Checkbox("##visible", &visible))
      doc.execute(setActorField(doc.project(), actor.id, &Actor::visible, visible,
                                std::string(visible ? "Show " : "Hide ") + actor.name));
    noteWidget("outliner/" + actor.id + "/visible");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Visible in the viewport");
    ImGui::SameLine();

    if (st.renamingActorId == actor.id) {
      if (st.focusRename) {
        ImGui::SetKeyboardFocusHere();
        st.focusRename = false;
      }
      ImGui::SetNextItemWidth(-1.0f);
      bool enter = ImGui::InputText("##rename", &st.renameBuffer,
                                    ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
      noteWidget("outliner/" + actor.id + "/rename");
      if (enter) {
        if (auto cmd = renameActorCommand(doc.project(), actor.id, st.renameBuffer)) doc.execute(std::move(cmd));
        st.renamingActorId.clear();
      } else if (ImGui::IsItemDeactivated() || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
        st.renamingActorId.clear();  // clicked away or Escape: cancel
      }
      ImGui::PopID();
      continue;
    }

    const Character* c = actorCharacter(doc, assets, actor);
    ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth;
    if (doc.selection.actorId == actor.id && doc.selection.node < 0) flags |= ImGuiTreeNodeFlags_Selected;
    const bool blob = actor.kind == ActorKind::BlobTree;
    if (blob) flags |= ImGuiTreeNodeFlags_DefaultOpen;
    else if (!c || c->roots.empty()) flags |= ImGuiTreeNodeFlags_Leaf;
    if (!actor.visible) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    bool open = ImGui::TreeNodeEx("##actor", flags, "%s", actor.name.c_str());
    if (!actor.visible) ImGui::PopStyleColor();
    noteWidget("outliner/" + actor.id);
    if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) doc.selection = {actor.id, -1};
    if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(0)) beginRename(st, doc, actor.id);
    if (ImGui::BeginPopupContextItem("##actor_menu")) {
      doc.selection = {actor.id, -1};
      if (ImGui::MenuItem("Rename")) beginRename(st, doc, actor.id);
      if (ImGui::MenuItem(actor.visible ? "Hide" : "Show"))
        doc.execute(setActorField(doc.project(), actor.id, &Actor::visible, !actor.visible,
                                  std::string(actor.visible ? "Hide " : "Show ") + actor.name));
      if (ImGui::MenuItem("Delete", shortcutHint(Action::DeleteSelection).c_str())) deleteId = actor.id;
      ImGui::EndPopup();
    }
    if (open && blob) {
      drawBlobTreeNodes(doc, actor.id, st.blob, status);
      ImGui::TreePop();
    } else if (open) {
      if (!actor.assetPath.empty() && !c) {
        const AssetCache::Entry& e = assets.get(doc.resolveAsset(actor.assetPath));
        ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
        ImGui::TextWrapped("%s", e.error.empty() ? "asset not loaded" : e.error.c_str());
        ImGui::PopStyleColor();
        noteWidget("outliner/" + actor.id + "/error");
      } else if (c) {
        std::vector<char> isJoint(c->nodes.size(), 0);
        for (const Skin& s : c->skins)
          for (int j : s.joints)
            if (j >= 0 && j < static_cast<int>(isJoint.size())) isJoint[j] = 1;
        for (int r : c->roots) drawNode(*c, r, isJoint, actor, doc, 0);
      }
      ImGui::TreePop();
    } else if (!actor.assetPath.empty() && !c) {
      // Collapsed: still flag the failure so it is not missed.
      ImGui::SameLine();
      ImGui::TextColored(kErrorColor, "(load error)");
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", assets.get(doc.resolveAsset(actor.assetPath)).error.c_str());
    }
    ImGui::PopID();
  }
  if (!deleteId.empty()) {
    if (auto cmd = deleteActorCommand(doc.project(), deleteId)) {
      doc.execute(std::move(cmd));
      if (doc.selection.actorId == deleteId) doc.selection = {};
    }
  }
  ImGui::End();
}

}  // namespace animorph
