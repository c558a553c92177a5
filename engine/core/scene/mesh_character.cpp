#include "core/scene/mesh_character.h"

namespace animorph {

std::shared_ptr<const Character> characterFromMesh(const TriangleMesh& tm, const std::string& name) {
  auto c = std::make_shared<Character>();
  c->sourcePath = name;
  Mesh m;
  m.name = name;
  m.positions = tm.positions;
  m.normals = tm.normals;
  m.indices = tm.indices;
  if (tm.colors.size() == tm.positions.size()) m.colors = tm.colors;  // linear, drawn as COLOR_0
  m.joints0.assign(m.positions.size(), glm::uvec4(0));
  m.weights0.assign(m.positions.size(), glm::vec4(1, 0, 0, 0));
  c->meshes.push_back(std::move(m));
  Node n;
  n.name = name;
  n.mesh = 0;
  c->nodes.push_back(n);
  c->roots = {0};
  return c;
}

}  // namespace animorph
