#pragma once
// The main menu bar: File, Edit, View, Help, with the shortcut of each item
// shown beside it (from the shortcut table). Returns what the user chose;
// EditorUI carries it out.
#include <string>
#include <vector>

#include "doc/document.h"
#include "shortcuts.h"

namespace animorph {

struct MenuResult {
  std::vector<Action> actions;
  std::string openRecentPath;  // File > Recent > path chosen, or empty
};

// Draws the bar; returns its height in pixels through heightPx.
MenuResult drawMenuBar(const Document& doc, const std::vector<std::string>& recentFiles, float& heightPx);

}  // namespace animorph
