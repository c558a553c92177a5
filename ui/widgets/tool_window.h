#pragma once
// A closable tool window (the curve editor, the correspondence editor, the
// weight paint tools): floating over the viewport, placed at pos / size the
// first time it opens after being closed; or docked, on a rectangle the layout
// gives it every frame. Its rectangle is recorded for automation.
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

// The docked form: at pos / size every frame, not movable or resizable (the
// layout's splitters size it), with a title bar and its close button.
// Returns as beginToolWindow; f.placeNext is left alone.
bool beginDockedToolWindow(const char* title, ImVec2 pos, ImVec2 size, const std::string& widgetKey,
                           ToolWindowFlags f);

}  // namespace animorph
