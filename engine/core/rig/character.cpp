#include "core/rig/character.h"

#include <set>

namespace animorph {

Bounds Mesh::bounds() const {
  Bounds b;
  for (const auto& p : positions) b.add(p);
  return b;
}

size_t Character::totalVertices() const {
  size_t n = 0;
  for (int node : meshNodes()) n += meshes[nodes[node].mesh].vertexCount();
  return n;
}

size_t Character::totalTriangles() const {
  size_t n = 0;
  for (int node : meshNodes()) n += meshes[nodes[node].mesh].triangleCount();
  return n;
}

size_t Character::totalJoints() const {
  std::set<int> joints;
  for (const auto& s : skins) joints.insert(s.joints.begin(), s.joints.end());
  return joints.size();
}

std::vector<int> Character::meshNodes() const {
  std::vector<int> out;
  std::vector<int> stack(roots.rbegin(), roots.rend());
  std::vector<bool> seen(nodes.size(), false);
  while (!stack.empty()) {
    int n = stack.back();
    stack.pop_back();
    if (n < 0 || n >= static_cast<int>(nodes.size()) || seen[n]) continue;
    seen[n] = true;
    if (nodes[n].mesh >= 0) out.push_back(n);
    for (auto it = nodes[n].children.rbegin(); it != nodes[n].children.rend(); ++it) stack.push_back(*it);
  }
  return out;
}

}  // namespace animorph
