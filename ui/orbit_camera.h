#pragma once
// A minimal orbit camera for the viewport (target, distance, yaw, pitch).
// Kept in this one file so it can be swapped for engine/core/view/camera.h.
// Units: metres and radians; right-handed, +Y up.
#include <glm/glm.hpp>

#include "math/bounds.h"

namespace animorph {

struct OrbitCamera {
  glm::vec3 target{0.0f, 1.0f, 0.0f};
  float distanceM = 6.0f;
  float yawRad = 0.6f;     // around +Y, 0 looks down -Z
  float pitchRad = -0.3f;  // negative looks down on the target
  float fovYRad = 0.7854f;
  float nearM = 0.01f;
  float farM = 1000.0f;

  glm::vec3 eye() const;
  glm::vec3 forward() const;  // unit, from eye to target
  glm::mat4 view() const;
  // Right-handed, depth 0..1 (Vulkan), Y not flipped (the renderer flips).
  glm::mat4 projection(float aspect) const;

  // Rotates around the target by a mouse drag in pixels.
  void orbit(float dxPx, float dyPx);
  // Moves target and eye so that the scene under the cursor follows the mouse.
  void pan(float dxPx, float dyPx, float viewportHeightPx);
  // Moves towards (positive) or away from the target; amount in pixels of drag.
  void dolly(float amountPx);
  // Wheel zoom: each notch (positive = away from the user) moves 15% closer.
  void zoomWheel(float notches);
  // Centres the target on b and backs off so its bounding sphere fills the view.
  // An empty b leaves the camera unchanged.
  void frame(const Bounds& b, float aspect);
};

}  // namespace animorph
