#pragma once
// Orbit camera of the 3D viewport (Maya-style tumble / track / dolly), its
// Vulkan matrices, and picking rays. Pure math.
#include <cstdint>
#include <optional>
#include <span>

#include <glm/glm.hpp>

#include "core/math/bounds.h"

namespace animorph {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
};

struct OrbitCamera {
  glm::vec3 target{0.0f};  // the point orbited around
  float yawRad = 0.6f;     // about +Y; 0 looks from +Z towards -Z
  float pitchRad = 0.35f;  // above the horizon (positive looks down), within +-kMaxPitchRad
  float distanceM = 5.0f;  // eye to target
  float fovYRad = 0.785398f;

  static constexpr float kMaxPitchRad = 1.5533f;  // 89 degrees: never flips over the pole
  static constexpr float kMinDistanceM = 1e-3f;
  static constexpr float kOrbitRadPerPixel = 0.006f;

  // Eye position in world space.
  glm::vec3 eye() const;
  // Unit vectors of the camera frame in world space.
  glm::vec3 forward() const;
  glm::vec3 right() const;
  glm::vec3 up() const;
  // Near and far planes, scaled with the distance so depth precision follows the zoom.
  float nearM() const;
  float farM() const;

  // World to view (right-handed, looking down -Z).
  glm::mat4 view() const;
  // Perspective for Vulkan clip space: y points down in NDC, depth 0 (near) .. 1 (far).
  glm::mat4 projection(float aspect) const;
  // projection(aspect) * view()
  glm::mat4 viewProjection(float aspect) const;

  // Tumble by a mouse drag of (dx, dy) pixels: right drag turns the scene left-to-right
  // like Maya, down drag looks more from above. Pitch is clamped.
  void orbit(float dxPixels, float dyPixels);
  // Track: moves target and eye so the point under the cursor at the target's depth
  // follows a drag of (dx, dy) pixels in a viewport viewportHeightPx pixels tall.
  void pan(float dxPixels, float dyPixels, float viewportHeightPx);
  // Dolly toward the target by wheel steps (positive: closer); each step scales the
  // distance by 0.85. Never reaches the target.
  void dolly(float steps);
  // Frames bounds (F key): looks at their centre from a distance at which their
  // bounding sphere fits the view of the given aspect, keeping yaw and pitch.
  // Empty bounds leave the camera unchanged.
  void frame(const Bounds& bounds, float aspect);

  // Window pixel (x right, y down, origin top-left of the viewport, pixel centres at
  // +0.5) of a world point; z is the Vulkan depth (0..1), outside 0..1 when clipped.
  glm::vec3 worldToPixel(const glm::vec3& world, glm::vec2 viewportPx) const;
  // The ray from the eye through pixel (x, y) of the viewport.
  Ray rayThroughPixel(float x, float y, glm::vec2 viewportPx) const;
};

struct TriangleHit {
  uint32_t triangle = 0;     // index of the triangle (indices[3*triangle ...])
  float distance = 0.0f;     // along the ray (the ray direction is unit length)
  glm::vec3 barycentric{0};  // weights of the triangle's three vertices
  glm::vec3 position{0};
};

// The nearest triangle hit by ray (both faces count), or nullopt. Indices out of
// range are skipped. Möller–Trumbore, O(triangles).
std::optional<TriangleHit> pickTriangle(const Ray& ray, std::span<const glm::vec3> positions,
                                        std::span<const uint32_t> indices);

}  // namespace animorph
