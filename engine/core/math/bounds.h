#pragma once
// Axis-aligned bounding box.
#include <glm/glm.hpp>
#include <limits>

namespace animorph {

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};

  bool empty() const { return min.x > max.x; }
  void add(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void add(const Bounds& b) {
    if (!b.empty()) { add(b.min); add(b.max); }
  }
  glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : 0.5f * (min + max); }
  glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }
  float diagonal() const { return glm::length(size()); }
};

}  // namespace animorph
