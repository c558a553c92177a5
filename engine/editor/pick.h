#pragma once
// Picking: which actor's posed mesh a ray hits first.
#include <optional>
#include <string>

#include "core/scene/scene_frame.h"
#include "core/camera/camera.h"

namespace animorph {

struct ScenePick {
  std::string actorId;
  int meshNode = -1;
  float distance = 0.0f;   // along the ray, metres
  glm::vec3 position{0.0f};
};

// Skins every mesh of frame on the CPU and returns the nearest hit, or
// nothing. O(vertices + triangles): meant for clicks, not per frame.
std::optional<ScenePick> pickScene(const SceneFrame& frame, const Ray& ray);

}  // namespace animorph
