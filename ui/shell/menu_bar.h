#pragma once
// The main menu bar: File, Edit, Create, Animorphosis, View, Help, with the shortcut of each item
// shown beside it (from the shortcut table). Returns what the user chose;
// EditorUI carries it out.
#include <optional>
#include <string>
#include <vector>

#include "core/blobtree/node_type.h"
#include "core/doc/document.h"
#include "ui/common/shortcuts.h"
#include "ui/viewport/viewport_mode.h"
#include "ui/viewport/weight_paint_tool.h"

namespace animorph {

struct MenuResult {
  std::vector<Action> actions;
  std::string openPath;  // File > Recent or Help > Demos: the project chosen, or empty
  std::optional<NodeType> addNodeType;  // Create > Add Node > type chosen
};

// Draws the bar; returns its height in pixels through heightPx. curveEditorShown
// checks View > Curve Editor, mode the viewport mode entries, correspondenceShown
// View > Correspondence Editor; demos lists the demo projects Help > Demos opens (disabled when
// there are none).
MenuResult drawMenuBar(const Document& doc, const std::vector<std::string>& recentFiles, float& heightPx,
                       bool curveEditorShown = false, const WeightPaintState& paint = {},
                       ViewportMode mode = ViewportMode::Object, bool correspondenceShown = false,
                       const std::vector<std::string>& demos = {});

}  // namespace animorph
