#pragma once
// The translate gizmo's three arrows, shared by the BlobTree gizmo (gizmo.h)
// and stand-in editing (standin_tool.h): laid out at a world point along three
// directions, kArrowPx long on screen, hovered and dragged with the left
// button; a drag reports the world offset along its arrow since the press.
#include <glm/glm.hpp>

#include "core/camera/camera.h"
#include "ui/viewport/viewport_input.h"

struct ImDrawList;

namespace animorph {

struct TranslateArrows {
  int hoverAxis = -1;  // arrow under the mouse (0..2), -1: none
  int dragAxis = -1;   // arrow being dragged
  glm::vec3 dragOrigin{0.0f}, dragDir{0.0f};  // world axis line of the drag
  float dragStartS = 0.0f;                    // mouse ray's closest parameter on it at the press
  bool hot() const { return hoverAxis >= 0 || dragAxis >= 0; }
};

// Where the arrows are on screen this frame.
struct ArrowsLayout {
  glm::vec3 origin{0.0f};
  glm::vec3 dirs[3];     // unit world directions
  glm::vec2 originPx{0.0f};
  glm::vec2 tipsPx[3];
  bool tipVisible[3] = {false, false, false};
  float worldPerPx = 0.0f;  // world length of one pixel at the origin's depth
};

enum class ArrowEvent { None, Started, Moved, Ended };

// Lays the arrows out at origin along dirs (zero directions become the world
// axes). False when origin is not in front of the camera.
bool layoutTranslateArrows(const OrbitCamera& camera, const ViewportRect& viewport, const glm::vec3& origin,
                           const glm::mat3& dirs, ArrowsLayout& out);

// One frame of hover (only when canHover), press, drag and release. While
// Started/Moved, offset is the world move along the dragged arrow since the
// press. widgetPrefix names the arrows in the widget map ("gizmo" gives
// gizmo/origin, gizmo/x, gizmo/y, gizmo/z).
ArrowEvent updateTranslateArrows(TranslateArrows& st, const ArrowsLayout& l, const OrbitCamera& camera,
                                 const ViewportRect& viewport, const PointerInput& in, bool canHover,
                                 const char* widgetPrefix, glm::vec3& offset);

// Red X, green Y, blue Z; the hovered or dragged one highlighted.
void drawTranslateArrows(ImDrawList* dl, const TranslateArrows& st, const ArrowsLayout& l);

}  // namespace animorph
