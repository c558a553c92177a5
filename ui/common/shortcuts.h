#pragma once
// Editor actions and the one shortcut table that the key handling, the menu
// hints and Help > Shortcuts all read. Keys are GLFW key codes as the GLFW
// backend writes them into ImGuiIO::KeysDown (letters are their ASCII
// upper-case codes).
#include <string>
#include <vector>

struct ImGuiIO;

namespace animorph {

enum class Action {
  New, Open, Save, SaveAs, ImportCharacter, SaveScreenshot, Export, Playblast, Quit,
  Undo, Redo, DeleteSelection, DuplicateSelection, NewBlobActor, ToggleCurveEditor,
  ToggleGrid, ToggleSkeleton, ToggleWireframe, ToggleAxes, ToggleStandins, ToggleStandinEdit, FrameSelection,
  PlayPause, StepBack, StepForward, GoToStart, GoToEnd,
  Preferences, About, ShowShortcuts,
  ToggleWeightPaint, ToggleWeightOverlay, ImportWeights,
  CreateAnimorphosis, ToggleCorrespondenceEditor, CreateMorph, BakeAnimorphosisKeys,
};

struct Shortcut {
  Action action;
  int key;  // GLFW key code
  bool ctrl = false;
  bool shift = false;
  bool alt = false;
  const char* description = "";
};

// Every shortcut, in the order Help > Shortcuts lists them. An action can
// have several (Redo: Ctrl+Shift+Z and Ctrl+Y).
const std::vector<Shortcut>& shortcutTable();

// "Ctrl+Shift+Z" for one shortcut.
std::string shortcutText(const Shortcut& s);
// Text of the first shortcut of action (for menu hints), or "" if it has none.
std::string shortcutHint(Action action);

// Actions whose shortcut was pressed this frame (key pressed, exact modifiers;
// key repeat for the frame steps). Empty while a text field has focus
// (io.WantTextInput). Call between ImGui::NewFrame and ImGui::Render.
std::vector<Action> pollShortcuts(const ImGuiIO& io);

}  // namespace animorph
