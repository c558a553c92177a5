#include "editor/standin_pick.h"

#include <algorithm>
#include <cmath>

namespace animorph {

namespace {

// First positive hit of the ray on the sphere (c, r).
std::optional<float> raySphere(const Ray& ray, const glm::vec3& c, float r) {
  glm::vec3 oc = ray.origin - c;
  float b = glm::dot(ray.direction, oc);
  float h = b * b - (glm::dot(oc, oc) - r * r);
  if (h < 0.0f) return std::nullopt;
  float t = -b - std::sqrt(h);
  if (t < 0.0f) return std::nullopt;
  return t;
}

float distToSegment2d(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  glm::vec2 ab = b - a;
  float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

}  // namespace

std::optional<float> rayCapsule(const Ray& ray, const glm::vec3& a, const glm::vec3& b, float r) {
  if (!(r > 0.0f)) return std::nullopt;
  const glm::vec3 ba = b - a, oa = ray.origin - a;
  const float baba = glm::dot(ba, ba), bard = glm::dot(ba, ray.direction), baoa = glm::dot(ba, oa);
  const float rdoa = glm::dot(ray.direction, oa), oaoa = glm::dot(oa, oa);
  const float qa = baba - bard * bard;
  std::optional<float> best;
  auto keep = [&](std::optional<float> t) {
    if (t && (!best || *t < *best)) best = t;
  };
  // The cylinder's side (skipped when the ray runs along the axis).
  if (baba > 0.0f && qa > 1e-9f * baba) {
    const float qb = baba * rdoa - baoa * bard, qc = baba * oaoa - baoa * baoa - r * r * baba;
    const float h = qb * qb - qa * qc;
    if (h >= 0.0f) {
      const float t = (-qb - std::sqrt(h)) / qa;
      const float y = baoa + t * bard;
      if (t >= 0.0f && y > 0.0f && y < baba) keep(t);
    }
  }
  keep(raySphere(ray, a, r));
  keep(raySphere(ray, b, r));
  return best;
}

std::optional<StandinPick> pickStandinSegment(const std::vector<StandinGuides>& guides, const OrbitCamera& camera,
                                              glm::vec2 viewportPx, glm::vec2 pixel, float maxPixels) {
  const Ray ray = camera.rayThroughPixel(pixel.x, pixel.y, viewportPx);
  std::optional<StandinPick> hit;
  for (const StandinGuides& g : guides)
    for (const StandinGuideSegment& s : g.segments)
      if (auto t = rayCapsule(ray, s.a, s.b, s.radius); t && (!hit || *t < hit->distance))
        hit = StandinPick{g.actorId, s.index, *t};
  if (hit) return hit;
  float bestPx = maxPixels;
  for (const StandinGuides& g : guides)
    for (const StandinGuideSegment& s : g.segments) {
      glm::vec3 pa = camera.worldToPixel(s.a, viewportPx), pb = camera.worldToPixel(s.b, viewportPx);
      if (pa.z < 0.0f || pa.z > 1.0f || pb.z < 0.0f || pb.z > 1.0f) continue;
      float d = distToSegment2d(pixel, glm::vec2(pa), glm::vec2(pb));
      if (d <= bestPx) {
        bestPx = d;
        hit = StandinPick{g.actorId, s.index, glm::length(0.5f * (s.a + s.b) - ray.origin)};
      }
    }
  return hit;
}

}  // namespace animorph
