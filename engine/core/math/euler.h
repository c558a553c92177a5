#pragma once
// XYZ Euler angles in degrees (R = Rz * Ry * Rx), the form artists edit
// rotations in; quaternions are what tracks store.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace animorph {

// Euler degrees of q (normalised first).
glm::vec3 eulerDegreesOf(const glm::quat& q);
// Unit quaternion of XYZ Euler degrees.
glm::quat quatFromEulerDegrees(const glm::vec3& deg);

}  // namespace animorph
