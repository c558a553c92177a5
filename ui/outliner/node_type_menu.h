#pragma once
// Menu items listing every BlobTree node type by category (Primitive,
// Operator, Space map, Meta-primitive), for the Create menu and the
// outliner's context menu. Call inside an open menu or popup.
#include <optional>
#include <string>

#include "core/blobtree/blob_tree.h"
#include "core/blobtree/node_type.h"

namespace animorph {

// Draws one submenu per category; returns the type clicked this frame.
// widgetPrefix names the items for automation ("menu/Add/sphere").
std::optional<NodeType> nodeTypeMenuItems(const std::string& widgetPrefix, bool enabled = true);

// Which node a new node of type goes under when `selected` is selected:
// selected itself when it can take another child, else its parent. -1 when
// neither can (the message says why).
int parentForNewNode(const BlobTree& tree, int selected, std::string* why = nullptr);

}  // namespace animorph
