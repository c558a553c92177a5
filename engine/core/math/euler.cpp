#include "core/math/euler.h"

#include <glm/gtx/euler_angles.hpp>

namespace animorph {

glm::vec3 eulerDegreesOf(const glm::quat& q) {
  glm::mat4 m = glm::mat4_cast(glm::normalize(q));
  float x = 0.0f, y = 0.0f, z = 0.0f;
  glm::extractEulerAngleZYX(m, z, y, x);  // R = Rz * Ry * Rx
  return glm::degrees(glm::vec3(x, y, z));
}

glm::quat quatFromEulerDegrees(const glm::vec3& deg) {
  glm::vec3 r = glm::radians(deg);
  return glm::normalize(glm::quat_cast(glm::eulerAngleZYX(r.z, r.y, r.x)));
}

}  // namespace animorph
