#include "core/math/transform.h"

#include <glm/gtc/matrix_transform.hpp>

namespace animorph {

glm::mat4 Transform::matrix() const {
  glm::mat4 m = glm::mat4_cast(rotation);
  m[0] *= scale.x;
  m[1] *= scale.y;
  m[2] *= scale.z;
  m[3] = glm::vec4(translation, 1.0f);
  return m;
}

Transform decompose(const glm::mat4& m) {
  Transform t;
  t.translation = glm::vec3(m[3]);
  glm::vec3 c0(m[0]), c1(m[1]), c2(m[2]);
  t.scale = {glm::length(c0), glm::length(c1), glm::length(c2)};
  if (glm::determinant(glm::mat3(m)) < 0.0f) t.scale.x = -t.scale.x;
  glm::mat3 r(c0 / t.scale.x, c1 / t.scale.y, c2 / t.scale.z);
  t.rotation = glm::normalize(glm::quat_cast(r));
  return t;
}

}  // namespace animorph
