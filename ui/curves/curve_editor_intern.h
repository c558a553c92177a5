#pragma once
// Private to the curve editor (ui/curves/curve_editor_*.cpp), split as Blender splits an editor:
// curve_editor_panel.cpp runs a frame of the window (source, navigation, the order of the parts),
// curve_editor_draw.cpp draws the toolbar, the channel list and the graph, curve_editor_edit.cpp
// turns the toolbar, the key menu, double-clicks and drags into commands, and
// curve_editor_select.cpp picks keys and handles and keeps the selection.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <imgui.h>

#include "ui/curves/curve_editor_panel.h"
#include "ui/curves/curve_source.h"

namespace animorph {

constexpr float kKeyPickPx = 6.0f;   // a click this close to a key (or handle) picks it
constexpr float kHandlePx = 40.0f;   // on-screen length of a tangent handle

// A key of a visible channel, where the graph draws it.
struct CurveKeyPx {
  KeyChannelRef ref;
  glm::vec2 px;
  KeyInterp interp;
  bool rotation;
};

// What the parts of one frame of the panel share: the source shown, its axis and channels, the
// graph's rectangle, the mouse and the keys on screen. Built by drawCurveEditorPanel.
struct CurveFrame {
  Document& doc;
  CurveEditorState& st;
  StatusMessage& status;
  const CurveSource& src;
  CurveAxis ax;
  std::vector<CurveChannel> channels;
  std::string mergeKey;  // drags of this source merge into one command
  ImVec2 g0{0.0f, 0.0f};     // graph's top-left corner (screen pixels)
  ImVec2 avail{0.0f, 0.0f};  // graph's size (pixels, at least 50 x 50)
  glm::vec2 mouse{0.0f};
  bool hovered = false;  // the mouse is over the graph
  bool active = false;   // the graph holds the mouse (a drag on it)
  std::vector<CurveKeyPx> keys{};
};

// ---- curve_editor_select.cpp
// True when the channel's visibility box is off.
bool hiddenChannel(const CurveEditorState& st, const CurveChannel& c);
// The selected keys (each once, whatever channels of it are selected).
std::vector<KeyRef> selectedKeys(const CurveEditorState& st);
// Drops selected keys that no longer exist (undo, edits elsewhere).
void pruneCurveSelection(CurveFrame& f);
// f.keys: the keys of the visible channels at their graph pixels (after this frame's zoom / pan).
void collectCurveKeys(CurveFrame& f);
// On-screen offset of a key's out handle (the in handle is its negative), kHandlePx long.
glm::vec2 handleDir(const CurveFrame& f, const KeyChannelRef& k);
// Whether the graph draws (and picks) the key's tangent handles: selected, not a rotation.
bool showsHandles(const CurveFrame& f, const CurveKeyPx& k);
// A left click on the graph (not adding a key): grabs a handle of a selected key, else picks a key
// (Shift toggles) and starts moving the selection, else starts a box selection.
void pressOnCurveGraph(CurveFrame& f);
// A right click on a key selects it (unless selected) and opens the key menu.
void rightClickCurveKey(CurveFrame& f);
// The left button released: a box selection selects the keys in it (Shift adds); a move or tangent
// drag ends its command.
void releaseCurveDrag(CurveFrame& f);

// ---- curve_editor_edit.cpp
// Runs fn on the source's tracks and executes the command; a refusal goes to the status line.
// Returns whether the edit happened.
bool runCurveEdit(CurveFrame& f, const std::string& label, const KeyEditFn& fn);
void setKeysInterp(CurveFrame& f, const std::vector<KeyRef>& keys, KeyInterp mode);
void setKeysTangentMode(CurveFrame& f, const std::vector<KeyRef>& keys, bool user);
// Deletes the keys and clears the selection.
void deleteCurveKeys(CurveFrame& f, const std::vector<KeyRef>& keys);
// Numeric entry of the single selected key's x and value (toolbar); commits on leaving a field.
void drawSelectedKeyEntry(CurveFrame& f);
// Double-click, or Ctrl+click off the keys: a key on the nearest visible curve at the mouse's x.
// Returns whether this frame's click was such a click (then nothing else handles it).
bool addCurveKeyOnClick(CurveFrame& f);
// While the left button is down: moves the dragged keys, or sets the dragged key's tangent.
void dragCurveKeys(CurveFrame& f);
// Del deletes the selected keys; the right-click menu of a key.
void curveKeyShortcuts(CurveFrame& f);
void drawCurveKeyMenu(CurveFrame& f);

// ---- curve_editor_draw.cpp
// The toolbar: interpolation and tangent buttons, Frame all, snapping, the key entry. Returns
// whether Frame all was pressed.
bool drawCurveToolbar(CurveFrame& f);
void drawCurveChannelList(CurveFrame& f);
// The graph: background, grid and labels, curves, playheads, keys and handles, the selection box.
void drawCurveGraph(const CurveFrame& f);

}  // namespace animorph
