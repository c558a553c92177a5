#include "render/particle_overlay.h"

#include <algorithm>
#include <cmath>

namespace animorph::gpu {

void addParticleMarkers(const ParticleDraw& draw, uint32_t rgba, LineBatch& lines) {
  const glm::mat3 linear(draw.model);
  // The model's scale, for the markers' size (a uniform scale in practice).
  const float scale = std::cbrt(std::max(1e-12f, std::abs(glm::determinant(linear))));
  for (size_t i = 0; i < draw.centres.size(); ++i) {
    const glm::vec3 c = glm::vec3(draw.model * glm::vec4(draw.centres[i], 1.0f));
    const float r = std::max(i < draw.radii.size() ? draw.radii[i] : 0.0f, 1e-3f) * scale;
    lines.line(c - glm::vec3(r, 0.0f, 0.0f), c + glm::vec3(r, 0.0f, 0.0f), rgba);
    lines.line(c - glm::vec3(0.0f, r, 0.0f), c + glm::vec3(0.0f, r, 0.0f), rgba);
    lines.line(c - glm::vec3(0.0f, 0.0f, r), c + glm::vec3(0.0f, 0.0f, r), rgba);
  }
}

}  // namespace animorph::gpu
