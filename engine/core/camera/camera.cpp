#include "core/camera/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace animorph {

glm::vec3 OrbitCamera::forward() const {
  // The eye sits at target - forward * distance.
  float cp = std::cos(pitchRad), sp = std::sin(pitchRad);
  return -glm::vec3(cp * std::sin(yawRad), sp, cp * std::cos(yawRad));
}

glm::vec3 OrbitCamera::right() const { return glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0))); }

glm::vec3 OrbitCamera::up() const { return glm::cross(right(), forward()); }

glm::vec3 OrbitCamera::eye() const { return target - forward() * distanceM; }

float OrbitCamera::nearM() const { return std::max(distanceM * 0.01f, 1e-5f); }

float OrbitCamera::farM() const { return std::max(distanceM * 200.0f, 10.0f); }

glm::mat4 OrbitCamera::view() const { return glm::lookAtRH(eye(), target, up()); }

glm::mat4 OrbitCamera::projection(float aspect) const {
  glm::mat4 p = glm::perspectiveRH_ZO(fovYRad, std::max(aspect, 1e-6f), nearM(), farM());
  p[1][1] = -p[1][1];  // Vulkan NDC: +y is down
  return p;
}

glm::mat4 OrbitCamera::viewProjection(float aspect) const { return projection(aspect) * view(); }

void OrbitCamera::orbit(float dx, float dy) {
  yawRad -= dx * kOrbitRadPerPixel;
  pitchRad = std::clamp(pitchRad + dy * kOrbitRadPerPixel, -kMaxPitchRad, kMaxPitchRad);
  yawRad = std::remainder(yawRad, 2.0f * 3.14159265f);
}

void OrbitCamera::pan(float dx, float dy, float viewportHeightPx) {
  float metresPerPixel = 2.0f * distanceM * std::tan(0.5f * fovYRad) / std::max(viewportHeightPx, 1.0f);
  // Dragging right moves the scene right, so the camera moves left; y pixels grow downwards.
  target += (-dx * right() + dy * up()) * metresPerPixel;
}

void OrbitCamera::dolly(float steps) {
  distanceM = std::max(distanceM * std::pow(0.85f, steps), kMinDistanceM);
}

void OrbitCamera::frame(const Bounds& b, float aspect) {
  if (b.empty()) return;
  target = b.center();
  float radius = std::max(0.5f * b.diagonal(), 1e-4f);
  float halfY = 0.5f * fovYRad;
  float halfX = std::atan(std::tan(halfY) * std::max(aspect, 1e-6f));
  distanceM = std::max(radius / std::sin(std::min(halfX, halfY)), kMinDistanceM);
}

glm::vec3 OrbitCamera::worldToPixel(const glm::vec3& world, glm::vec2 vp) const {
  glm::vec4 clip = viewProjection(vp.x / vp.y) * glm::vec4(world, 1.0f);
  glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * vp.x, (ndc.y * 0.5f + 0.5f) * vp.y, ndc.z};
}

Ray OrbitCamera::rayThroughPixel(float x, float y, glm::vec2 vp) const {
  float aspect = vp.x / vp.y;
  float ndcX = 2.0f * x / vp.x - 1.0f;
  float ndcY = 2.0f * y / vp.y - 1.0f;  // down
  float tanY = std::tan(0.5f * fovYRad);
  glm::vec3 dir = forward() + right() * (ndcX * tanY * aspect) - up() * (ndcY * tanY);
  return {eye(), glm::normalize(dir)};
}

std::optional<TriangleHit> pickTriangle(const Ray& ray, std::span<const glm::vec3> positions,
                                        std::span<const uint32_t> indices) {
  std::optional<TriangleHit> best;
  const size_t n = positions.size();
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
    if (i0 >= n || i1 >= n || i2 >= n) continue;
    const glm::vec3 &a = positions[i0], &b = positions[i1], &c = positions[i2];
    glm::vec3 e1 = b - a, e2 = c - a;
    glm::vec3 p = glm::cross(ray.direction, e2);
    float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;  // parallel or degenerate
    float inv = 1.0f / det;
    glm::vec3 s = ray.origin - a;
    float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) continue;
    glm::vec3 q = glm::cross(s, e1);
    float v = glm::dot(ray.direction, q) * inv;
    if (v < 0.0f || u + v > 1.0f) continue;
    float dist = glm::dot(e2, q) * inv;
    if (dist <= 0.0f || (best && dist >= best->distance)) continue;
    best = TriangleHit{static_cast<uint32_t>(t / 3), dist, {1.0f - u - v, u, v}, ray.origin + dist * ray.direction};
  }
  return best;
}

}  // namespace animorph
