#include "ui/outliner/blob_outliner.h"

#include <cstring>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/doc/blobtree_commands.h"
#include "ui/outliner/node_type_menu.h"
#include "ui/common/shortcuts.h"
#include "ui/widgets/widget_rects.h"
#include "ui/common/command_result.h"

namespace animorph {

namespace {

constexpr const char* kPayload = "AM_BLOB_NODE";

struct NodePayload {
  char actorId[96];
  int node;
};

// What the user asked for this frame; done after the tree has been drawn.
struct PendingEdit {
  enum Kind { None, Add, Duplicate, Delete, Reparent, Rename } kind = None;
  int node = -1;
  int target = -1;
  NodeType type = NodeType::Sphere;
  std::string name;
};

void drawNode(Document& doc, const std::string& actorId, const BlobNode& n, BlobOutlinerState& st,
              PendingEdit& edit, int depth) {
  if (depth > 256) return;
  ImGui::PushID(n.id);
  const std::string key = "outliner/" + actorId + "/blob/" + std::to_string(n.id);
  if (st.renamingActor == actorId && st.renamingNode == n.id) {
    if (st.focusRename) {
      ImGui::SetKeyboardFocusHere();
      st.focusRename = false;
    }
    ImGui::SetNextItemWidth(-1.0f);
    bool enter = ImGui::InputText("##rename", &st.renameBuffer,
                                  ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
    noteWidget(key + "/rename");
    if (enter) {
      edit = {PendingEdit::Rename, n.id, -1, n.type, st.renameBuffer};
      st.renamingNode = -1;
    } else if (ImGui::IsItemDeactivated() || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
      st.renamingNode = -1;
    }
    ImGui::PopID();
    return;
  }

  // Double-click renames, so only the arrow opens; the top two levels start open.
  ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth;
  if (depth < 2) flags |= ImGuiTreeNodeFlags_DefaultOpen;
  if (n.children.empty()) flags |= ImGuiTreeNodeFlags_Leaf;
  if (doc.selection.actorId == actorId && doc.selection.node == n.id) flags |= ImGuiTreeNodeFlags_Selected;
  const char* type = nodeTypeInfo(n.type).name;
  std::string label = (n.name.empty() ? std::string(type) : n.name) + "  (" + type + ")";
  bool open = ImGui::TreeNodeEx("##node", flags, "%s", label.c_str());
  noteWidget(key);
  if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) doc.selection = {actorId, n.id};
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(0)) beginBlobNodeRename(st, doc, actorId, n.id);

  if (ImGui::BeginDragDropSource()) {
    NodePayload p{};
    std::strncpy(p.actorId, actorId.c_str(), sizeof p.actorId - 1);
    p.node = n.id;
    ImGui::SetDragDropPayload(kPayload, &p, sizeof p);
    ImGui::Text("Move %s", label.c_str());
    ImGui::EndDragDropSource();
  }
  if (ImGui::BeginDragDropTarget()) {
    if (const ImGuiPayload* pl = ImGui::AcceptDragDropPayload(kPayload)) {
      NodePayload p;
      std::memcpy(&p, pl->Data, sizeof p);
      if (actorId == p.actorId && p.node != n.id) edit = {PendingEdit::Reparent, p.node, n.id, n.type, {}};
    }
    ImGui::EndDragDropTarget();
  }
  if (ImGui::BeginPopupContextItem("##node_menu")) {
    doc.selection = {actorId, n.id};
    ImGui::TextDisabled("Add child");
    if (auto t = nodeTypeMenuItems(key + "/add/")) edit = {PendingEdit::Add, n.id, -1, *t, {}};
    ImGui::Separator();
    if (ImGui::MenuItem("Rename")) beginBlobNodeRename(st, doc, actorId, n.id);
    if (ImGui::MenuItem("Duplicate", shortcutHint(Action::DuplicateSelection).c_str()))
      edit = {PendingEdit::Duplicate, n.id, -1, n.type, {}};
    noteWidget(key + "/duplicate");
    if (ImGui::MenuItem("Delete", shortcutHint(Action::DeleteSelection).c_str()))
      edit = {PendingEdit::Delete, n.id, -1, n.type, {}};
    noteWidget(key + "/delete");
    ImGui::EndPopup();
  }
  if (open) {
    for (const auto& c : n.children) drawNode(doc, actorId, c, st, edit, depth + 1);
    ImGui::TreePop();
  }
  ImGui::PopID();
}

}  // namespace

void beginBlobNodeRename(BlobOutlinerState& st, const Document& doc, const std::string& actorId, int nodeId) {
  const Actor* a = doc.project().findActor(actorId);
  const BlobNode* n = a ? a->blobTree.find(nodeId) : nullptr;
  if (!n) return;
  st.renamingActor = actorId;
  st.renamingNode = nodeId;
  st.renameBuffer = n->name;
  st.focusRename = true;
}

void drawBlobTreeNodes(Document& doc, const std::string& actorId, BlobOutlinerState& st, StatusMessage& status) {
  const Actor* actor = doc.project().findActor(actorId);
  if (!actor || actor->kind != ActorKind::BlobTree) return;
  const BlobTree tree = actor->blobTree;  // copy: an edit below replaces it
  PendingEdit edit;
  drawNode(doc, actorId, tree.root, st, edit, 0);

  Result<std::unique_ptr<Command>> cmd = Error{""};
  int select = -1;
  switch (edit.kind) {
    case PendingEdit::None: return;
    case PendingEdit::Add: {
      std::string why;
      int parent = parentForNewNode(tree, edit.node, &why);
      if (parent < 0) {
        status = {why, true};
        return;
      }
      cmd = addBlobNodeCommand(doc.project(), actorId, parent, edit.type, &select);
      break;
    }
    case PendingEdit::Duplicate: cmd = duplicateBlobNodeCommand(doc.project(), actorId, edit.node, &select); break;
    case PendingEdit::Delete: cmd = deleteBlobNodeCommand(doc.project(), actorId, edit.node); break;
    case PendingEdit::Reparent:
      cmd = reparentBlobNodeCommand(doc.project(), actorId, edit.node, edit.target);
      select = edit.node;
      break;
    case PendingEdit::Rename: cmd = renameBlobNodeCommand(doc.project(), actorId, edit.node, edit.name); break;
  }
  if (!executeOrReport(doc, std::move(cmd), status, /*announce=*/true)) return;
  if (edit.kind == PendingEdit::Delete && doc.selection.actorId == actorId) doc.selection = {actorId, -1};
  if (select >= 0) doc.selection = {actorId, select};
}

}  // namespace animorph
