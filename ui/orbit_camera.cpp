#include "orbit_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace animorph {
namespace {
constexpr float kOrbitRadPerPx = 0.008f;
constexpr float kPitchLimit = 1.55f;  // just under 90 degrees: no flip over the pole
constexpr float kMinDistanceM = 1e-3f;
constexpr float kMaxDistanceM = 1e5f;
}  // namespace

glm::vec3 OrbitCamera::forward() const {
  float cp = std::cos(pitchRad);
  return glm::normalize(glm::vec3(-std::sin(yawRad) * cp, std::sin(pitchRad), -std::cos(yawRad) * cp));
}

glm::vec3 OrbitCamera::eye() const { return target - forward() * distanceM; }

glm::mat4 OrbitCamera::view() const { return glm::lookAtRH(eye(), target, glm::vec3(0.0f, 1.0f, 0.0f)); }

glm::mat4 OrbitCamera::projection(float aspect) const {
  return glm::perspectiveRH_ZO(fovYRad, aspect > 0.0f ? aspect : 1.0f, nearM, farM);
}

void OrbitCamera::orbit(float dxPx, float dyPx) {
  yawRad = std::remainder(yawRad - dxPx * kOrbitRadPerPx, 2.0f * glm::pi<float>());
  pitchRad = std::clamp(pitchRad - dyPx * kOrbitRadPerPx, -kPitchLimit, kPitchLimit);
}

void OrbitCamera::pan(float dxPx, float dyPx, float viewportHeightPx) {
  if (viewportHeightPx <= 0.0f) return;
  float metresPerPx = 2.0f * distanceM * std::tan(0.5f * fovYRad) / viewportHeightPx;
  glm::vec3 f = forward();
  glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0.0f, 1.0f, 0.0f)));
  glm::vec3 up = glm::cross(right, f);
  target += (-dxPx * right + dyPx * up) * metresPerPx;
}

void OrbitCamera::dolly(float amountPx) {
  distanceM = std::clamp(distanceM * std::exp(-amountPx * 0.005f), kMinDistanceM, kMaxDistanceM);
}

void OrbitCamera::zoomWheel(float notches) {
  distanceM = std::clamp(distanceM * std::pow(0.85f, notches), kMinDistanceM, kMaxDistanceM);
}

void OrbitCamera::frame(const Bounds& b, float aspect) {
  if (b.empty()) return;
  target = b.center();
  float radius = std::max(0.5f * b.diagonal(), 0.01f);
  // The narrower of the two fields of view must hold the sphere.
  float halfFovY = 0.5f * fovYRad;
  float halfFovX = std::atan(std::tan(halfFovY) * (aspect > 0.0f ? aspect : 1.0f));
  float halfFov = std::min(halfFovY, halfFovX);
  distanceM = std::clamp(radius / std::sin(halfFov) * 1.05f, kMinDistanceM, kMaxDistanceM);
  farM = std::max(farM, distanceM + 4.0f * radius);
}

}  // namespace animorph
