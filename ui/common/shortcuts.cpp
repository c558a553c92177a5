#include "ui/common/shortcuts.h"

#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace animorph {

const std::vector<Shortcut>& shortcutTable() {
  static const std::vector<Shortcut> table = {
      {Action::New, GLFW_KEY_N, true, false, false, "New project"},
      {Action::Open, GLFW_KEY_O, true, false, false, "Open project"},
      {Action::Save, GLFW_KEY_S, true, false, false, "Save project"},
      {Action::SaveAs, GLFW_KEY_S, true, true, false, "Save project as"},
      {Action::Quit, GLFW_KEY_Q, true, false, false, "Quit"},
      {Action::Undo, GLFW_KEY_Z, true, false, false, "Undo"},
      {Action::Redo, GLFW_KEY_Z, true, true, false, "Redo"},
      {Action::Redo, GLFW_KEY_Y, true, false, false, "Redo"},
      {Action::DeleteSelection, GLFW_KEY_DELETE, false, false, false,
       "Delete the selected actor or BlobTree node (keys, in the curve editor; the link, in the correspondence "
       "editor)"},
      {Action::DuplicateSelection, GLFW_KEY_D, true, false, false, "Duplicate the selected BlobTree node"},
      {Action::ToggleCurveEditor, GLFW_KEY_G, true, false, false, "Show / hide the curve editor"},
      {Action::PlayPause, GLFW_KEY_SPACE, false, false, false, "Play / pause"},
      {Action::StepBack, GLFW_KEY_LEFT, false, false, false, "Previous frame"},
      {Action::StepForward, GLFW_KEY_RIGHT, false, false, false, "Next frame"},
      {Action::GoToStart, GLFW_KEY_HOME, false, false, false, "Go to range start"},
      {Action::GoToEnd, GLFW_KEY_END, false, false, false, "Go to range end"},
      {Action::FrameSelection, GLFW_KEY_F, false, false, false, "Frame the selection"},
      {Action::ToggleStandinEdit, GLFW_KEY_E, false, false, false, "Stand-in edit mode on / off"},
      {Action::ToggleWeightPaint, GLFW_KEY_P, false, false, false,
       "Weight Paint mode (LMB paints; [ ] or F set the brush radius)"},
  };
  return table;
}

namespace {
std::string keyName(int key) {
  switch (key) {
    case GLFW_KEY_DELETE: return "Del";
    case GLFW_KEY_SPACE: return "Space";
    case GLFW_KEY_LEFT: return "Left";
    case GLFW_KEY_RIGHT: return "Right";
    case GLFW_KEY_HOME: return "Home";
    case GLFW_KEY_END: return "End";
    default:
      if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, static_cast<char>(key));
      if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, static_cast<char>(key));
      return "Key" + std::to_string(key);
  }
}

bool repeats(Action a) { return a == Action::StepBack || a == Action::StepForward; }
}  // namespace

std::string shortcutText(const Shortcut& s) {
  std::string t;
  if (s.ctrl) t += "Ctrl+";
  if (s.shift) t += "Shift+";
  if (s.alt) t += "Alt+";
  return t + keyName(s.key);
}

std::string shortcutHint(Action action) {
  for (const Shortcut& s : shortcutTable())
    if (s.action == action) return shortcutText(s);
  return {};
}

std::vector<Action> pollShortcuts(const ImGuiIO& io) {
  std::vector<Action> out;
  if (io.WantTextInput) return out;
  for (const Shortcut& s : shortcutTable()) {
    if (s.ctrl != io.KeyCtrl || s.shift != io.KeyShift || s.alt != io.KeyAlt) continue;
    if (ImGui::IsKeyPressed(s.key, repeats(s.action))) out.push_back(s.action);
  }
  return out;
}

}  // namespace animorph
