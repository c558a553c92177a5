#pragma once
// Translation / rotation / scale, composed as T * R * S (glTF order).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace animorph {

struct Transform {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};

  glm::mat4 matrix() const;
  bool operator==(const Transform&) const = default;
};

// Splits an affine matrix into T, R, S (no shear). Used for glTF nodes given as matrices.
Transform decompose(const glm::mat4& m);

}  // namespace animorph
