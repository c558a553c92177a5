#pragma once
// Stand-in editing in the viewport (the Stand-in edit mode): a click on a
// capsule selects that segment (and its actor); the selected segment shows a
// handle at each end and at its middle (click one: the translate arrows move
// that end, or the whole segment from the middle) and a radius handle on its
// outline (drag it sideways: the radius follows the mouse). Moves are made at
// the current frame's pose and stored in the segment's joint space; one drag
// is one undo step.
#include <string>

#include <glm/glm.hpp>

#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "core/scene/standin_guides.h"
#include "ui/common/status_bar.h"
#include "ui/viewport/translate_arrows.h"
#include "core/camera/camera.h"
#include "ui/viewport/viewport_input.h"

struct ImDrawList;

namespace animorph {

enum class StandinPart { Whole, A, B };  // what the translate arrows move

// How the selected segment (the Document's selection: Selection::segment) is being edited.
struct StandinToolState {
  StandinPart part = StandinPart::Whole;
  TranslateArrows arrows;
  bool hoverHandle = false;  // an end, middle or radius handle is under the mouse
  bool radiusDrag = false;
  bool scrollList = false;   // the inspector's list scrolls to the selection (set by a viewport pick)
  // Set by the inspector's Refit all: the actor whose whole stand-in EditorUI refits as a
  // background job (shell/editor_jobs.cpp); cleared when the job starts.
  std::string refitAllRequest;
  StandinSegment dragStart;       // the segment when the drag started
  StandinGuideSegment dragGuide;  // its pose then
  glm::vec2 radiusDirPx{1.0f, 0.0f};  // screen direction the radius handle moves along
  glm::vec2 radiusPressPx{0.0f};
  float radiusWorldPerPx = 0.0f;
  // True while the mouse is on a handle or dragging: the viewport must not orbit or pick.
  bool hot() const { return arrows.hot() || hoverHandle || radiusDrag; }
};

// The document's selected stand-in segment (Selection::segment) when it still exists and the
// selection is the actor itself (not one of its joints); -1 otherwise.
int selectedStandinSegment(const Document& doc);

// Scene time of the document's current frame (seconds).
double documentTimeSec(const Document& doc);

// The posed stand-ins of the document's morph actors at the current frame.
std::vector<StandinGuides> documentStandinGuides(const Document& doc, AssetCache& assets);

// Draws and runs the handles of the selected segment (nothing without one).
void drawStandinTool(Document& doc, AssetCache& assets, const OrbitCamera& camera, const ViewportRect& viewport,
                     const PointerInput& in, StandinToolState& st, StatusMessage& status, ImDrawList* dl);

// A viewport click in the Stand-in edit mode: selects the segment under it
// (and its actor) and returns true; false when there is none (the segment is
// deselected and the click goes on to the ordinary picking).
bool pickStandinClick(Document& doc, AssetCache& assets, const OrbitCamera& camera, const ViewportRect& viewport,
                      glm::vec2 windowPos, StandinToolState& st);

}  // namespace animorph
