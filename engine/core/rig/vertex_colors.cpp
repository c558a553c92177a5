#include "core/rig/vertex_colors.h"

#include "core/math/color.h"

namespace animorph {

std::vector<int> vertexMaterials(const Mesh& m) {
  std::vector<int> out(m.vertexCount(), m.material);
  std::vector<char> seen(m.vertexCount(), 0);
  for (const Mesh::Part& p : m.parts) {
    if (p.firstIndex > m.indices.size() || p.indexCount > m.indices.size() - p.firstIndex) continue;
    for (size_t i = p.firstIndex; i < size_t(p.firstIndex) + p.indexCount; ++i) {
      const uint32_t v = m.indices[i];
      if (v < out.size() && !seen[v]) seen[v] = 1, out[v] = p.material;
    }
  }
  return out;
}

namespace {

// Whether material k gives a surface a colour of its own (a factor other than white, or a texture).
bool materialColoured(const Character& c, int k) {
  if (k < 0 || size_t(k) >= c.materials.size()) return false;
  const Material& m = c.materials[size_t(k)];
  const int t = m.baseColorTexture;
  const bool texture = t >= 0 && size_t(t) < c.textures.size() && c.textures[size_t(t)].valid();
  return texture || glm::any(glm::lessThan(glm::vec3(m.baseColorFactor), glm::vec3(0.999f)));
}

// The colour of vertex v of m drawn with material k (-1: none), linear.
glm::vec3 vertexColor(const Character& c, const Mesh& m, size_t v, int k) {
  const bool coloured = materialColoured(c, k) || !m.colors.empty();
  if (!coloured) return srgbToLinear(kViewportGreySrgb);
  glm::vec3 base(1.0f);
  if (k >= 0 && size_t(k) < c.materials.size()) {
    const Material& mat = c.materials[size_t(k)];
    base = glm::vec3(mat.baseColorFactor);
    const int t = mat.baseColorTexture;
    if (t >= 0 && size_t(t) < c.textures.size() && c.textures[size_t(t)].valid() && v < m.texcoords0.size())
      base *= srgbToLinear(glm::vec3(sampleTexture(c.textures[size_t(t)], m.texcoords0[v])));
  }
  if (v < m.colors.size()) base *= glm::vec3(m.colors[v]);
  return glm::clamp(base, 0.0f, 1.0f);
}

}  // namespace

std::vector<glm::vec4> characterVertexColors(const Character& c) {
  bool any = false;
  for (int node : c.meshNodes()) {
    const Mesh& m = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
    any |= m.colors.size() == m.vertexCount() && !m.colors.empty();
    for (int k : vertexMaterials(m)) any |= materialColoured(c, k);
  }
  if (!any) return {};
  std::vector<glm::vec4> out;
  for (int node : c.meshNodes()) {
    const Mesh& m = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
    const std::vector<int> mats = vertexMaterials(m);
    for (size_t v = 0; v < m.vertexCount(); ++v) out.push_back(glm::vec4(vertexColor(c, m, v, mats[v]), 1.0f));
  }
  return out;
}

}  // namespace animorph
