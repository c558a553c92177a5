#include "ui/outliner/node_type_menu.h"

#include <cstring>

#include <imgui.h>

#include "core/blobtree/tree_edit.h"
#include "core/blobtree/validate.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

std::optional<NodeType> nodeTypeMenuItems(const std::string& widgetPrefix, bool enabled) {
  static const struct {
    const char* category;
    const char* label;
  } kCategories[] = {{"primitive", "Primitive"}, {"operator", "Operator"}, {"map", "Space map"}, {"meta", "Meta-primitive"}};
  std::optional<NodeType> chosen;
  for (const auto& c : kCategories) {
    ImVec2 pos = ImGui::GetCursorScreenPos();
    bool open = ImGui::BeginMenu(c.label, enabled);
    if (WidgetRects* r = activeWidgetRects())
      r->set(widgetPrefix + c.label, {{pos.x, pos.y}, {pos.x + ImGui::GetWindowWidth(), pos.y + ImGui::GetFrameHeight()}});
    if (!open) continue;
    for (const NodeTypeInfo& info : allNodeTypes()) {
      if (std::strcmp(info.category, c.category) != 0) continue;
      if (ImGui::MenuItem(info.name)) chosen = info.type;
      noteWidget(widgetPrefix + info.name);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", info.doc);
    }
    ImGui::EndMenu();
  }
  return chosen;
}

int parentForNewNode(const BlobTree& tree, int selected, std::string* why) {
  auto canTake = [](const BlobNode& n) {
    int mx = nodeTypeInfo(n.type).maxChildren;
    return mx < 0 || int(n.children.size()) < mx;
  };
  const BlobNode* n = tree.find(selected);
  if (!n) n = &tree.root;
  if (canTake(*n)) return n->id;
  const BlobNode* parent = findParent(tree, n->id);
  if (parent && canTake(*parent)) return parent->id;
  if (why) *why = describeNode(*n) + " and its parent take no more children";
  return -1;
}

}  // namespace animorph
