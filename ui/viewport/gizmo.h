#pragma once
// Translate gizmo for the selected BlobTree node's position-like parameters
// (point and sphere centres, segment / triangle corners, frame translation,
// curve control points). Drawn with ImGui draw-list primitives over the 3D
// viewport (the viewport window's own list, so floating windows such as the
// curve editor stay on top of it; the foreground list when none is given): three arrows along the parameter space's axes (red X, green Y,
// blue Z) at the active parameter, and a small circle at each of the node's
// other positions (click one to move the gizmo there). Dragging an arrow
// moves the point along that axis; one drag is one undo step; an animated
// parameter gets a key at the current frame.
#include <string>

#include <glm/glm.hpp>

#include "core/blobtree/tree_edit.h"
#include "core/doc/document.h"
#include "ui/common/status_bar.h"
#include "ui/viewport/translate_arrows.h"
#include "core/camera/camera.h"
#include "ui/viewport/viewport_input.h"

struct ImDrawList;

namespace animorph {

struct GizmoState {
  std::string actorId;  // node the gizmo belongs to
  int node = -1;
  ParamAddress active;  // parameter it sits on (reset when the node changes)
  bool hoverHandle = false;
  TranslateArrows arrows;
  glm::vec3 dragStartLocal{0.0f};
  glm::mat3 dragInvJacobian{1.0f};
  double dragTimeSec = 0.0;
  // True while the mouse is on the gizmo or dragging it: the viewport must not orbit or pick.
  bool hot() const { return arrows.hot() || hoverHandle; }
};

// Position-like parameters of a node, in drawing order.
std::vector<ParamAddress> gizmoParams(const BlobTree& tree, int nodeId);

// Draws and runs the gizmo for doc's selection (nothing unless a BlobTree node
// is selected). in: this frame's pointer (blockedByUi: another window is over
// the viewport). Refused edits report to status.
void drawGizmo(Document& doc, const OrbitCamera& camera, const ViewportRect& viewport, const PointerInput& in,
               GizmoState& st, StatusMessage& status, ImDrawList* drawList = nullptr);

}  // namespace animorph
