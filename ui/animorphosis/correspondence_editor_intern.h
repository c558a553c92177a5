#pragma once
// Private to the correspondence editor (ui/animorphosis/correspondence_*.cpp), split as Blender
// splits an editor: correspondence_editor_panel.cpp runs a frame of the window (tabs, the graph's
// layout and navigation, the order of the parts), correspondence_editor_draw.cpp draws the
// toolbar, the rows and the wires, correspondence_editor_edit.cpp turns drops, menus, the knife
// and Del into commands, correspondence_editor_select.cpp picks rows and wires and keeps the
// selection, and correspondence_chain_tab.cpp shows a morph's chain matching.
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>
#include <imgui.h>

#include "core/doc/document.h"
#include "core/project/animorphosis_project.h"
#include "ui/animorphosis/animorphosis_panel.h"

namespace animorph {

constexpr float kCorrIndent = 14.0f;  // per depth level
constexpr float kCorrArrowW = 14.0f;  // the open / close arrow at the start of a row
constexpr float kCorrPickPx = 6.0f;   // a click this close to a wire selects it
constexpr int kCorrWireSamples = 24;  // segments of a wire's Bezier for picking and cutting

// A visible row of one tree.
struct CorrRow {
  const BlobNode* node = nullptr;
  int depth = 0;
  bool open = false;
  glm::vec2 min{0.0f}, max{0.0f};  // screen rect, set when laid out
};

// One tree's visible rows, and for every node the row showing it (its nearest
// visible ancestor-or-self).
struct CorrTreeRows {
  std::vector<CorrRow> rows;
  std::unordered_map<int, int> rowOf;
  std::unordered_map<int, int> linksIn;  // links inside each node's sub-tree (itself included)
  std::unordered_map<int, int> parentOf;
};

// A link's wire on screen: a cubic Bezier from the source's socket p0 to the target's p3.
struct CorrWire {
  int link = -1;  // index in the graph's links (or suggestions); -1: the wire being dragged
  glm::vec2 p0{0.0f}, p3{0.0f};
  glm::vec2 c1() const;
  glm::vec2 c2() const;
  glm::vec2 at(float t) const;
};

// What the parts of one frame of the graph share: the trees, the graph as it was when the frame
// began (commands may replace the project's), the layout in content units (pixels at zoom 1), the
// view, the mouse and the wires on screen. Built by drawCorrespondenceEditor.
struct CorrFrame {
  Document& doc;
  CorrespondenceEditorState& st;
  StatusMessage& status;
  const Actor& src;
  const Actor& dst;
  const AnimorphosisSetup setup;  // a copy: commands below may replace the project's
  ImDrawList* dl = nullptr;
  glm::vec2 mouse{0.0f};
  CorrTreeRows ra{}, rb{};  // the source's rows, the target's
  float rowH = 0.0f;
  ImVec2 origin{0.0f, 0.0f};  // the graph's top-left (screen pixels)
  glm::vec2 avail{1.0f};      // the graph's size (pixels)
  float gap = 0.0f, colW = 0.0f;  // the gap the wires cross, each tree's column
  glm::vec2 content{1.0f};        // the whole layout's size
  float z = 1.0f;                 // the zoom after this frame's navigation
  float clipTop = 0.0f, clipBottom = 0.0f;  // the graph window's visible screen rows
  bool rowHovered = false;    // the mouse is over a row
  bool graphHovered = false;  // the mouse is over the graph window
  std::vector<CorrWire> wires{}, suggestionWires{};

  // Content units to screen pixels (after zoom and pan).
  glm::vec2 toScreen(float cx, float cy) const;
  // Where wires attach to the row showing the source node (A) or the target node (B).
  glm::vec2 socketA(int id) const;
  glm::vec2 socketB(int id) const;
};

// What a row's button saw this frame (correspondence_editor_select.cpp), for drawing it.
struct CorrRowHit {
  bool hovered = false;
  bool dropTarget = false;  // a wire dragged from the other tree is over it
};

// ---- correspondence_editor_select.cpp
// The visible rows of a tree (the top kDefaultOpenDepth levels open, toggled ones flipped) with the
// link counts of the graph's side (sourceSide: nodeA, else nodeB).
CorrTreeRows buildCorrRows(const BlobTree& tree, const std::set<int>& toggled, const CorrespondenceGraph& g,
                           bool sourceSide);
// Forgets the toggles and the selection when the trees change; drops a selected link that is gone.
void keepCorrSelection(CorrespondenceEditorState& st, const AnimorphosisSetup& m);
// The row's invisible button: hover, a click on the arrow (open / close) or the name (the node
// becomes the document's selection), the start of a wire drag. side: 0 source, 1 target.
CorrRowHit pressCorrRow(CorrFrame& f, const CorrRow& r, int side, float indentX);
// A left or right click on the graph (not on a row, no drag, no Ctrl): selects the wire or
// suggestion under the mouse (a double-click accepts a suggestion, a right-click opens its menu),
// or clears the selection.
void clickCorrWires(CorrFrame& f);
// Distance in pixels from p to the wire's curve.
float corrWireDistance(const CorrWire& w, glm::vec2 p);
// True when the wire crosses the trail (a polyline in screen pixels).
bool corrWireCrossesTrail(const CorrWire& w, const std::vector<glm::vec2>& trail);

// ---- correspondence_editor_edit.cpp
// Executes cmd; a refusal goes to the status line; on success note is appended to its label.
void runCorrCommand(Document& doc, Result<std::unique_ptr<Command>> cmd, StatusMessage& status,
                    std::string note = {});
// The left button released over a row of the other tree links the dragged node to it (selected).
void dropCorrWire(CorrFrame& f);
// The right-click menus of a suggestion (Accept) and of a link (Cut, Own / Inherit s(u)).
void drawCorrSuggestionMenu(CorrFrame& f);
void drawCorrWireMenu(CorrFrame& f);
// Ctrl+right-drag: a knife; on release the links its trail crosses are cut, as one undo step.
void cutCorrWiresWithKnife(CorrFrame& f);
// Del cuts the selected link while the editor has the focus.
void deleteSelectedCorrLink(Document& doc, CorrespondenceEditorState& st, StatusMessage& status);

// ---- correspondence_editor_draw.cpp
// The toolbar: Auto-map, Bake, Ghosts, Cut, Accept all, the counts and the selected link or
// suggestion with its s(u) choice.
void drawCorrToolbar(Document& doc, const BlobTree& a, const BlobTree& b, CorrespondenceEditorState& st,
                     StatusMessage& status);
// The trees' titles; then each tree's rows (button via pressCorrRow, arrow, name, kind, badge,
// socket). side: 0 source (column x0..x1), 1 target.
void drawCorrHeaders(const CorrFrame& f);
void drawCorrRows(CorrFrame& f, int side, float x0, float x1);
// The links' wires (f.wires: the ones on screen) and the suggestions' dashed ones
// (f.suggestionWires).
void drawCorrLinkWires(CorrFrame& f);
void drawCorrSuggestionWires(CorrFrame& f);
// The wire being dragged from a row to the mouse.
void drawDraggedCorrWire(const CorrFrame& f);
// The knife's trail.
void drawCorrKnifeTrail(const CorrFrame& f);

// ---- correspondence_chain_tab.cpp
// With both a morph by chains and an animorphosis, a tab bar; returns whether the morph's chain
// tab is the one showing (always when only the morph has one).
bool showsMorphChainTab(bool chains, bool graph);
// The morph's chain matching (drawChainMatching, widgets noted corr/chains/...).
void drawMorphChainTab(Document& doc, MorphPanelState& morph);

}  // namespace animorph
