#include "core/poly/clip_mesh.h"

#include <cassert>
#include <unordered_map>

namespace animorph {

size_t appendClippedMesh(const TriangleMesh& mesh, const std::vector<float>& value, TriangleMesh& out) {
  assert(value.size() == mesh.positions.size());
  const size_t nv = mesh.positions.size();
  const bool normals = mesh.normals.size() == nv && (out.positions.empty() || out.normals.size() == out.positions.size());
  const bool colors = mesh.colors.size() == nv && (out.positions.empty() || out.colors.size() == out.positions.size());
  if (!normals) out.normals.clear();
  if (!colors) out.colors.clear();
  std::vector<uint32_t> kept(nv, UINT32_MAX);  // vertex of mesh -> vertex of out
  auto keep = [&](uint32_t v) {
    if (kept[v] == UINT32_MAX) {
      kept[v] = uint32_t(out.positions.size());
      out.positions.push_back(mesh.positions[v]);
      if (normals) out.normals.push_back(mesh.normals[v]);
      if (colors) out.colors.push_back(mesh.colors[v]);
    }
    return kept[v];
  };
  std::unordered_map<uint64_t, uint32_t> cuts;  // edge (lo << 32 | hi) -> its crossing's vertex in out
  auto cut = [&](uint32_t a, uint32_t b) {
    const uint32_t lo = std::min(a, b), hi = std::max(a, b);
    const uint64_t key = (uint64_t(lo) << 32) | hi;
    auto it = cuts.find(key);
    if (it != cuts.end()) return it->second;
    const float va = value[lo], vb = value[hi];
    const float t = va == vb ? 0.5f : va / (va - vb);  // where the value crosses 0, from lo
    const uint32_t id = uint32_t(out.positions.size());
    out.positions.push_back(glm::mix(mesh.positions[lo], mesh.positions[hi], t));
    if (normals) {
      const glm::vec3 n = glm::mix(mesh.normals[lo], mesh.normals[hi], t);
      const float len = glm::length(n);
      out.normals.push_back(len > 1e-12f ? n / len : mesh.normals[lo]);
    }
    if (colors) out.colors.push_back(glm::mix(mesh.colors[lo], mesh.colors[hi], t));
    cuts.emplace(key, id);
    return id;
  };
  size_t dropped = 0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const uint32_t v[3] = {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
    const bool in[3] = {value[v[0]] <= 0.0f, value[v[1]] <= 0.0f, value[v[2]] <= 0.0f};
    const int count = int(in[0]) + int(in[1]) + int(in[2]);
    if (count == 0) {
      ++dropped;
      continue;
    }
    if (count == 3) {
      for (uint32_t x : v) out.indices.push_back(keep(x));
      continue;
    }
    // Rotate so that the lone vertex (the one kept when count is 1, dropped when 2) comes first;
    // the winding stays as it was.
    const bool lone = count == 1;
    int r = 0;
    while (in[r] != lone) ++r;
    const uint32_t a = v[r], b = v[(r + 1) % 3], c = v[(r + 2) % 3];
    const uint32_t ab = cut(a, b), ca = cut(c, a);
    if (count == 1) {  // a kept: the triangle a, ab, ca
      out.indices.insert(out.indices.end(), {keep(a), ab, ca});
    } else {  // a dropped: the quad ab, b, c, ca
      const uint32_t kb = keep(b), kc = keep(c);
      out.indices.insert(out.indices.end(), {ab, kb, kc, ab, kc, ca});
    }
  }
  return dropped;
}

}  // namespace animorph
