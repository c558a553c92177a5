#include "editor/blob_pick.h"

namespace animorph {

std::optional<BlobGuidePick> pickBlobGuide(const SceneFrame& frame, const OrbitCamera& camera, glm::vec2 viewportPx,
                                           glm::vec2 pixel, float maxPixels) {
  std::optional<BlobGuidePick> best;
  auto consider = [&](const std::string& actorId, const glm::vec3& world, int node) {
    glm::vec3 p = camera.worldToPixel(world, viewportPx);
    if (p.z < 0.0f || p.z > 1.0f) return;
    float d = glm::length(glm::vec2(p) - pixel);
    if (d <= maxPixels && (!best || d < best->pixelDistance)) best = BlobGuidePick{actorId, node, d};
  };
  for (const BlobGuides& g : frame.blobGuides.get()) {
    for (const auto& m : g.markers) consider(g.actorId, m.position, m.node);
    for (const auto& a : g.axes) consider(g.actorId, a.origin, a.node);
  }
  return best;
}

std::optional<ScenePick> pickBlobSurface(const std::string& actorId, const glm::mat4& model, const TriangleMesh& mesh,
                                         const Ray& ray) {
  if (mesh.indices.empty()) return std::nullopt;
  // Into the actor's space; distances are scaled back through the direction's length.
  glm::mat4 inv = glm::inverse(model);
  Ray local;
  local.origin = glm::vec3(inv * glm::vec4(ray.origin, 1.0f));
  glm::vec3 dir = glm::vec3(inv * glm::vec4(ray.direction, 0.0f));
  float scale = glm::length(dir);
  if (!(scale > 0.0f)) return std::nullopt;
  local.direction = dir / scale;
  auto hit = pickTriangle(local, mesh.positions, mesh.indices);
  if (!hit) return std::nullopt;
  ScenePick p;
  p.actorId = actorId;
  p.distance = hit->distance / scale;
  p.position = glm::vec3(model * glm::vec4(hit->position, 1.0f));
  return p;
}

}  // namespace animorph
