#pragma once
// Colour conventions shared by the BlobTree colours, the polygonised meshes' vertex colours and
// the renderer: parameters and pickers hold sRGB components in [0, 1]; meshes and blending hold
// linear light, converted with the renderer's power 2.2 (shaders/include/mesh_shading.glsl), so a
// vertex colour srgbToLinear(c) draws exactly like a draw colour c.
#include <cmath>

#include <glm/glm.hpp>

namespace animorph {

// The clay tone BlobTree surfaces are drawn in when they carry no colour of their own (sRGB).
inline constexpr glm::vec3 kClayColorSrgb{0.55f, 0.68f, 0.82f};

// sRGB components (clamped to [0, 1]) to linear light: c^2.2 per component.
inline glm::vec3 srgbToLinear(const glm::vec3& c) {
  const glm::vec3 k = glm::clamp(c, 0.0f, 1.0f);
  return {std::pow(k.x, 2.2f), std::pow(k.y, 2.2f), std::pow(k.z, 2.2f)};
}

// Linear light (clamped to [0, 1]) to sRGB components: c^(1/2.2) per component.
inline glm::vec3 linearToSrgb(const glm::vec3& c) {
  const glm::vec3 k = glm::clamp(c, 0.0f, 1.0f);
  return {std::pow(k.x, 1.0f / 2.2f), std::pow(k.y, 1.0f / 2.2f), std::pow(k.z, 1.0f / 2.2f)};
}

}  // namespace animorph
