#pragma once
// Coloured line segments collected on the CPU each frame (skeleton overlay,
// bounds, guides) and drawn by the scene renderer. Pure CPU data.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/math/bounds.h"
#include "core/rig/character.h"

namespace animorph::gpu {

struct LineVertex {
  glm::vec3 position;  // world space
  uint32_t rgba;       // packRgba(): r in the low byte
};
static_assert(sizeof(LineVertex) == 16);

// Packs a colour with components in [0, 1] (clamped) into RGBA8, r in the low byte.
uint32_t packRgba(const glm::vec4& color);

class LineBatch {
 public:
  void clear() { vertices_.clear(); }
  // One segment from a to b.
  void line(const glm::vec3& a, const glm::vec3& b, uint32_t rgba);
  // The 12 edges of an octahedron of the given radius (a joint marker).
  void octahedron(const glm::vec3& center, float radius, uint32_t rgba);
  // The 12 edges of an axis-aligned box (nothing for empty bounds).
  void box(const Bounds& bounds, uint32_t rgba);
  const std::vector<LineVertex>& vertices() const { return vertices_; }
  size_t segmentCount() const { return vertices_.size() / 2; }

 private:
  std::vector<LineVertex> vertices_;
};

// Skeleton overlay of character posed by globals (poseGlobals()): an octahedron
// of jointRadius at every skin joint and a line from each joint to its parent
// joint. Joints referenced by no skin are skipped.
void addSkeleton(LineBatch& batch, const Character& character, const std::vector<glm::mat4>& globals,
                 float jointRadius, uint32_t boneRgba, uint32_t jointRgba);

}  // namespace animorph::gpu
