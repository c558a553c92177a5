#pragma once
// Mouse control of the 3D viewport: camera orbit/pan/dolly/zoom in the Maya
// and Blender bindings, and click-to-pick requests for the app.
//   Maya:    Alt+LMB orbit, Alt+MMB pan, Alt+RMB dolly, wheel zoom
//   Blender: MMB orbit, Shift+MMB pan, Ctrl+MMB dolly, wheel zoom
// The two sets do not overlap (Maya's all hold Alt), so with
// Preferences::otherSchemeToo both work at once.
#include <optional>

#include <glm/glm.hpp>

#include "core/camera/camera.h"
#include "ui/common/prefs.h"

struct ImGuiIO;

namespace animorph {

// A rectangle in window pixels (origin top-left).
struct ViewportRect {
  glm::vec2 min{0.0f};
  glm::vec2 size{0.0f};
  bool contains(glm::vec2 p) const {
    return p.x >= min.x && p.y >= min.y && p.x < min.x + size.x && p.y < min.y + size.y;
  }
  float aspect() const { return size.y > 0.0f ? size.x / size.y : 1.0f; }
};

// One frame of mouse state. Buttons: 0 left, 1 right, 2 middle (ImGui order).
struct PointerInput {
  glm::vec2 pos{0.0f};
  glm::vec2 delta{0.0f};
  bool down[3] = {false, false, false};
  bool pressed[3] = {false, false, false};   // went down this frame
  bool released[3] = {false, false, false};  // went up this frame
  float wheel = 0.0f;                        // notches, positive = away from the user
  bool alt = false, shift = false, ctrl = false;
  bool blockedByUi = false;  // another window or a popup is under the mouse
};

// The app casts a ray through this point against the skinned meshes and sets
// Document::selection (an empty hit clears it unless extend).
struct PickRequest {
  glm::vec2 windowPos{0.0f};  // pixels, window coordinates
  glm::vec2 ndc{0.0f};        // -1..1 over the viewport, +Y up
  bool extend = false;        // Shift held: add to the selection
};

enum class CameraDrag { None, Orbit, Pan, Dolly };

class ViewportInput {
 public:
  // Applies one frame of input: drags that start inside rect move camera
  // (and keep doing so outside it until released); a left click without Alt
  // that moves less than a few pixels returns a pick request.
  std::optional<PickRequest> update(const PointerInput& in, const ViewportRect& rect, CameraScheme scheme,
                                    bool otherSchemeToo, OrbitCamera& camera);
  CameraDrag activeDrag() const { return drag_; }

 private:
  CameraDrag drag_ = CameraDrag::None;
  int dragButton_ = -1;
  bool clickCandidate_ = false;
  glm::vec2 pressPos_{0.0f};
};

// Which camera drag a button press with these modifiers starts (None if it
// starts none).
CameraDrag cameraDragFor(int button, bool alt, bool shift, bool ctrl, CameraScheme scheme, bool otherSchemeToo);

// PointerInput from ImGui's io (mouse state of the current frame).
PointerInput pointerFromImGui(const ImGuiIO& io, bool blockedByUi);

}  // namespace animorph
