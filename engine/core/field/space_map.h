#pragma once
// Maps from world space into a child's space: affine frames (translation,
// scale, quaternion rotation) and Barr warps (twist, taper, bend). A node under
// a map is evaluated at toLocal(x); its gradient comes back by the chain rule
// grad_world = J^T grad_local with J = d toLocal / dx (analytic for all kinds).
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/math/bounds.h"

namespace animorph {

enum class SpaceMapKind : uint8_t { Affine, Twist, Taper, Bend };

struct SpaceMap {
  SpaceMapKind kind = SpaceMapKind::Affine;
  // Affine: local = linear * (x - origin). Warps: linear's rows are the warp
  // frame (e_x, e_y = bend direction, e_z = axis a -> b), origin = a.
  glm::mat3 linear{1.0f};
  glm::vec3 origin{0.0f};
  glm::mat3 forwardLinear{1.0f};  // affine: inverse of linear (R * S)
  float length = 1.0f;            // warps: |b - a|
  float k0 = 0.0f;                // twist: rate (rad/m); taper: scale at a; bend: curvature (1/m)
  float k1 = 0.0f;                // taper: scale at b

  // World point -> child point; J (optional) receives d(child)/d(world).
  glm::vec3 toLocal(const glm::vec3& x, glm::mat3* J = nullptr) const;
  // Child point -> world point (the deformation itself).
  glm::vec3 toWorld(const glm::vec3& c) const;
  // World-space box enclosing the image of a child-space box (conservative for warps).
  Bounds worldBounds(const Bounds& child) const;
  // An upper bound of |J| (how much the map stretches distances) on the world
  // ball (centre, radius); infinite where no bound is known.
  float localStretchBound(const glm::vec3& centre, float radius) const;
};

// Frame T * R * S: a child point c appears at translation + rotation * (scale * c).
// Scale components must be non-zero.
SpaceMap makeAffineMap(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale);
// Twist by `angle` radians about the axis a -> b, growing linearly from a to b (constant outside).
SpaceMap makeTwistMap(const glm::vec3& a, const glm::vec3& b, float angle);
// Taper: cross-sections scaled by scaleA at a, scaleB at b (linear between, constant outside). Scales > 0.
SpaceMap makeTaperMap(const glm::vec3& a, const glm::vec3& b, float scaleA, float scaleB);
// Bend the axis a -> b by `angle` radians towards `direction` (made perpendicular to the axis).
SpaceMap makeBendMap(const glm::vec3& a, const glm::vec3& b, float angle, const glm::vec3& direction);

}  // namespace animorph
