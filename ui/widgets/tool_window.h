#pragma once
// A closable floating tool window over the viewport (the curve editor, the
// correspondence editor): placed at pos / size the first time it opens after
// being closed, its rectangle recorded for automation.
#include <string>

#include <imgui.h>

namespace animorph {

struct ToolWindowFlags {
  bool& visible;    // shown; the close button clears it
  bool& placeNext;  // place it at pos / size when it next opens
  bool& focused;    // set: the window or a child of it has the keyboard focus
};

// Begins the window. Returns true when its contents are to be drawn (call
// ImGui::End() after them); false when it is hidden or collapsed (nothing to end).
bool beginToolWindow(const char* title, ImVec2 pos, ImVec2 size, const std::string& widgetKey, ToolWindowFlags f);

}  // namespace animorph
