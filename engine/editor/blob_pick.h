#pragma once
// Picking of BlobTree actors: their polygonised preview surfaces, and the
// markers of their skeleton overlay (clicking a marker selects its node).
#include <optional>
#include <string>

#include "core/poly/mesh.h"
#include "editor/pick.h"

namespace animorph {

struct BlobGuidePick {
  std::string actorId;
  int node = -1;
  float pixelDistance = 0.0f;
};

// The guide marker or axes origin of frame nearest to pixel (viewport pixels)
// within maxPixels, in front of the camera; nothing when none is that close.
std::optional<BlobGuidePick> pickBlobGuide(const SceneFrame& frame, const OrbitCamera& camera, glm::vec2 viewportPx,
                                           glm::vec2 pixel, float maxPixels = 8.0f);

// The nearest hit of ray on a preview surface (mesh in the actor's space, drawn with model).
std::optional<ScenePick> pickBlobSurface(const std::string& actorId, const glm::mat4& model, const TriangleMesh& mesh,
                                         const Ray& ray);

}  // namespace animorph
