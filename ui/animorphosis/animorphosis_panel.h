#pragma once
// The editor side of the project's animorphosis (docs/animorphosis.md):
//  * Create > Animorphosis...: a modal that picks the source and target among
//    the project's BlobTree actors, the interval in frames and whether the
//    correspondence is proposed automatically; one undoable step.
//  * The correspondence editor (View > Correspondence Editor): the two trees
//    side by side as collapsible hierarchies, the links as wires between the
//    rows (automatic ones coloured by confidence, artist ones thick and blue,
//    the selected one white). Drag from a node of one tree onto a node of the
//    other: link; click a wire: select it; Del, right-click > Cut, or a
//    Ctrl+right-drag across wires: cut; the wheel zooms around the mouse, a
//    middle drag pans, F frames all (as in the curve editor); Auto-map:
//    propose links again keeping the artist's (a background job: progress,
//    Cancel; its result one undoable command); Bake to key-frame actor: the
//    animorphosis as a new key-framed BlobTree actor (Animorphosis menu too);
//    Ghosts: the viewport also shows A(t) and B(t), translucent (saved in the
//    project's animorphosis, undoable).
//    Suggestions -- links auto-map found too uncertain to apply -- are dashed
//    violet wires: click one to select it, then Accept (or double-click it, or
//    right-click > Accept); Accept all applies every one that keeps the graph
//    valid; each is one undo step.
//    A node with k links shows "x k"; the top of an unlinked
//    sub-tree says "shrinks" (source) or "grows" (target). A selected link can
//    get its own s(u), which the curve editor then shows beside the global one.
//    The node under the mouse has its skeleton highlighted in the viewport.
//  * The interval on the timeline ruler: a band with two draggable markers.
// Every edit is an undoable command; a refused one puts the validator's
// message in the status bar.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/animorphosis/auto_correspond.h"
#include "core/doc/document.h"
#include "ui/inspector/morph_panel.h"
#include "ui/common/layout.h"
#include "ui/common/status_bar.h"

namespace animorph {

struct CreateAnimorphosisState {
  bool openNext = false;  // open the modal on the next draw
  bool isOpen = false;
  std::string sourceActorId, targetActorId;
  int startFrame = 24, endFrame = 72;
  bool autoMap = true;
  std::string error;  // the last refusal, shown in the modal
  // Create was pressed with automatic correspondence: the editor proposes the graph off the UI
  // thread (the fields above say what to create) and applies the animorphosis as one step.
  bool createRequested = false;
};

struct CorrespondenceLinkRef {
  int nodeA = -1, nodeB = -1;
  bool operator==(const CorrespondenceLinkRef&) const = default;
};

// Suggestions (links auto-map proposed below its confidence threshold, not applied) are drawn as
// dashed wires in this colour (ImGui's packed ABGR: a light violet), apart from the applied links'
// solid red-to-green (automatic, by confidence) and blue (artist) wires.
inline constexpr unsigned kSuggestionWireColor = 0xE6FF8CC8u;

struct CorrespondenceEditorState {
  bool visible = false;
  bool placeNext = true;  // position the window over the viewport next time it opens
  bool focused = false;   // the window had keyboard focus this frame (Del is its own then)
  std::optional<CorrespondenceLinkRef> selected;
  // The selected suggestion (click its dashed wire; Accept, or a double-click, applies it).
  std::optional<CorrespondenceLinkRef> selectedSuggestion;
  Selection hovered;  // the node whose row is under the mouse (the viewport highlights its skeleton); none: empty
  // Rows whose open state differs from the default (the top three levels open).
  std::set<int> toggledA, toggledB;
  std::string treesKey;   // "source->target" the toggles belong to
  // A wire being dragged from a row: the side (0: source, 1: target) and node id.
  int dragSide = -1, dragNode = -1;
  // A Ctrl+right-drag cutting wires: its trail in window pixels.
  std::vector<glm::vec2> cutTrail;
  // View: rows and columns scaled by zoom around the graph's top-left, then
  // moved by pan (pixels). Wheel: zoom around the mouse; middle drag: pan;
  // F: frame all (every visible row fits the graph).
  float zoom = 1.0f;
  glm::vec2 pan{0.0f};
  bool frameAllNext = false;
  // The toolbar's Bake to key-frame actor was pressed; the editor starts the job.
  bool bakeRequested = false;
  // The toolbar's Auto-map was pressed; the editor starts the job (autoMapSettings, then one command).
  bool autoMapRequested = false;
};

// Auto-map's settings for the project's animorphosis: each clip sampled from where its actor is at
// the interval's start. Needs a valid animorphosis (checkAnimorphosis).
AutoCorrespondSettings autoMapSettings(const Project& p);
// What the status line adds to Auto-map's label: ": N proposed (mean confidence C), S suggested,
// K artist links kept".
std::string autoMapNote(const AutoCorrespondReport& report);

// The modal; call every frame. On success it opens the correspondence editor; with automatic
// correspondence it checks the choice, closes and sets st.createRequested instead.
void drawCreateAnimorphosisPopup(Document& doc, CreateAnimorphosisState& st, CorrespondenceEditorState& editor,
                                 StatusMessage& status);
// Fills the modal's fields from the project (its BlobTree actors, the current
// animorphosis or the middle half of the range) and opens it next draw.
void openCreateAnimorphosis(const Document& doc, CreateAnimorphosisState& st);

// The correspondence editor window when visible, docked on area (the layout's correspondence
// rectangle below the viewport). It edits the
// animorphosis' graph; a morph by skeleton correspondence has its chain matching there too
// (drawChainMatching on morph, the inspector's morph state: widgets noted corr/chains/...), on a
// tab of its own when the project has both.
void drawCorrespondenceEditor(const LayoutRect& area, Document& doc, CorrespondenceEditorState& st,
                              MorphPanelState& morph, StatusMessage& status);


}  // namespace animorph
