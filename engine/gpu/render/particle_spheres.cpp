#include "gpu/render/particle_spheres.h"

#include <algorithm>
#include <cmath>

#include "gpu/render/line_batch.h"

namespace animorph::gpu {

ParticleSpheresDraw particleSpheres(const ParticleDraw& draw, const glm::vec4& color, bool selected) {
  ParticleSpheresDraw out;
  out.color = color;
  out.selected = selected;
  const glm::mat3 linear(draw.model);
  // The model's scale, for the radii (a uniform scale in practice).
  const float scale = std::cbrt(std::max(1e-12f, std::abs(glm::determinant(linear))));
  out.spheres.resize(draw.centres.size());
  for (size_t i = 0; i < draw.centres.size(); ++i) {
    const glm::vec3 c = glm::vec3(draw.model * glm::vec4(draw.centres[i], 1.0f));
    const float r = std::max(i < draw.radii.size() ? draw.radii[i] : 0.0f, 1e-3f) * scale;
    out.spheres[i] = glm::vec4(c, r);
  }
  if (draw.colors.size() == draw.centres.size()) {
    out.colors.resize(draw.colors.size());
    for (size_t i = 0; i < draw.colors.size(); ++i)
      out.colors[i] = packRgba(glm::vec4(glm::clamp(draw.colors[i], 0.0f, 1.0f), 1.0f));
  }
  return out;
}

}  // namespace animorph::gpu
