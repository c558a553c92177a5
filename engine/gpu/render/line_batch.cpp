#include "gpu/render/line_batch.h"

#include <algorithm>

namespace animorph::gpu {

uint32_t packRgba(const glm::vec4& c) {
  auto byte = [](float v) { return static_cast<uint32_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
  return byte(c.r) | (byte(c.g) << 8) | (byte(c.b) << 16) | (byte(c.a) << 24);
}

void LineBatch::line(const glm::vec3& a, const glm::vec3& b, uint32_t rgba) {
  vertices_.push_back({a, rgba});
  vertices_.push_back({b, rgba});
}

void LineBatch::octahedron(const glm::vec3& c, float r, uint32_t rgba) {
  const glm::vec3 tips[6] = {c + glm::vec3(r, 0, 0), c - glm::vec3(r, 0, 0), c + glm::vec3(0, r, 0),
                             c - glm::vec3(0, r, 0), c + glm::vec3(0, 0, r), c - glm::vec3(0, 0, r)};
  // The equator (x/z tips) and the edges from it to both poles (y tips).
  const int ring[4] = {0, 4, 1, 5};
  for (int i = 0; i < 4; ++i) {
    line(tips[ring[i]], tips[ring[(i + 1) % 4]], rgba);
    line(tips[ring[i]], tips[2], rgba);
    line(tips[ring[i]], tips[3], rgba);
  }
}

void LineBatch::box(const Bounds& b, uint32_t rgba) {
  if (b.empty()) return;
  auto corner = [&](int i) {
    return glm::vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
  };
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) line(corner(i), corner(i | bit), rgba);
}

void addSkeleton(LineBatch& batch, const Character& c, const std::vector<glm::mat4>& globals, float jointRadius,
                 uint32_t boneRgba, uint32_t jointRgba) {
  std::vector<bool> isJoint(c.nodes.size(), false);
  for (const Skin& s : c.skins)
    for (int j : s.joints)
      if (j >= 0 && j < static_cast<int>(c.nodes.size())) isJoint[j] = true;
  for (size_t j = 0; j < c.nodes.size() && j < globals.size(); ++j) {
    if (!isJoint[j]) continue;
    glm::vec3 p = glm::vec3(globals[j][3]);
    batch.octahedron(p, jointRadius, jointRgba);
    int parent = c.nodes[j].parent;
    if (parent >= 0 && parent < static_cast<int>(globals.size()) && isJoint[parent])
      batch.line(glm::vec3(globals[parent][3]), p, boneRgba);
  }
}

}  // namespace animorph::gpu
