#pragma once
// Picking stand-in segments in the viewport: a ray against each posed
// segment's capsule (its radius around the axis), with the axis line within a
// few pixels as a fallback for capsules too thin to hit.
#include <optional>
#include <string>
#include <vector>

#include "core/scene/standin_guides.h"
#include "core/camera/camera.h"

namespace animorph {

// Distance along ray (unit direction) to its first entry into the capsule of
// radius r around segment [a, b]; nothing when it misses or the capsule is behind.
std::optional<float> rayCapsule(const Ray& ray, const glm::vec3& a, const glm::vec3& b, float r);

struct StandinPick {
  std::string actorId;
  int segment = -1;
  float distance = 0.0f;  // along the ray (m); for an axis-line pick, to the axis point
};

// The segment under pixel (viewport pixels): the nearest capsule the pixel's
// ray enters, else the axis nearest to pixel within maxPixels; nothing when neither.
std::optional<StandinPick> pickStandinSegment(const std::vector<StandinGuides>& guides, const OrbitCamera& camera,
                                              glm::vec2 viewportPx, glm::vec2 pixel, float maxPixels = 6.0f);

}  // namespace animorph
