#pragma once
// Curve editor (View > Curve Editor, Ctrl+G): the tracks of a CurveSource
// (curve_source.h) as curves: the selected BlobTree node's animated
// parameters over the tree's time (in frames), or, with the morph (or its
// source / target actor) selected, the morph's easing, blend, noise amplitude
// and keyed segment tracks over a normalised progress u (0..1); while the
// correspondence editor is open, the animorphosis' s(u) curves. Left: the
// channels with visibility boxes (x red, y green, z blue; rotations as Euler
// degrees). Right: the graph, with the current frame (or its u) as playhead.
//   click a key: select it (Shift: add / remove); drag on empty space: box
//   select (Shift adds); double-click (or Ctrl+click): a key on the nearest
//   visible curve at that x; drag keys: move them (snapped to whole frames, or 0.01 of u,
//   unless Ctrl is held); Del: delete the selected keys; handles of selected Hermite keys:
//   drag to set the slope (the key switches to user tangents); right-click a
//   key: interpolation (constant / linear / Hermite), auto / user tangents,
//   delete; F: frame every curve; wheel: zoom time, Ctrl+wheel: zoom values;
//   middle drag: pan. The toolbar has the same commands and numeric entry of
//   the selected key's frame and value. Every edit is one undoable command
//   (one per drag).
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <any>

#include "core/anim/key_edit.h"
#include "core/doc/document.h"
#include "ui/common/layout.h"
#include "ui/common/status_bar.h"

namespace animorph {

struct CurveEditorState {
  bool visible = false;
  bool placeNext = true;  // position the window over the bottom area next time it opens
  // View: x across (frames of tree time, or progress u), values up.
  double frame0 = -2.0, frame1 = 50.0;
  double value0 = -1.0, value1 = 1.0;
  bool frameAllNext = true;  // frame every curve on the next draw
  std::string sourceId;      // CurveSource::id() of what is shown
  std::set<KeyChannelRef> selection;
  std::set<std::pair<ParamAddress, int>> hidden;  // (track, channel) not drawn
  bool snap = true;                               // whole frames (0.01 of u) when moving keys

  enum class Drag { None, Move, Tangent, Box, Pan };
  Drag drag = Drag::None;
  glm::vec2 dragStart{0.0f};
  std::any dragOriginal;                // the source's snapshot when a move / tangent drag began
  std::vector<KeyChannelRef> dragKeys;  // what the drag moves, as refs into dragOriginal
  KeyChannelRef dragAnchor;             // the key under the mouse (snapping follows it)
  int tangentSide = 1;                  // +1: out handle, -1: in handle
  double lastDt = 0.0;
  double lastDv = 0.0;
  bool dragChanged = false;

  bool focused = false;  // the window had keyboard focus this frame (Del / F are its own then)
  // Set each frame by the correspondence editor while it is open and no
  // BlobTree node is selected: show the animorphosis' s curves instead of the
  // selection's (the global s, and the link a -> b's own s when it has one).
  bool animorphosis = false;
  int animorphosisLinkA = -1, animorphosisLinkB = -1;
  // Graph rectangle of the last frame (window pixels).
  glm::vec2 graphMin{0.0f}, graphMax{0.0f};
};

// Graph pixel of an (x, value) point, and back, for the state's view and graph rectangle.
glm::vec2 curveToPixel(const CurveEditorState& st, double frame, double value);
glm::dvec2 pixelToCurve(const CurveEditorState& st, glm::vec2 px);

// Draws the window when visible, docked on area (the layout's curves
// rectangle below the viewport). Refused edits report to status.
void drawCurveEditorPanel(const LayoutRect& area, Document& doc, CurveEditorState& st, StatusMessage& status);

}  // namespace animorph
