#include "util/mesh_checks.h"

#include <map>
#include <numeric>
#include <tuple>

namespace animorph::test {

Topology weldedTopology(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  std::vector<uint32_t> weld(positions.size());
  for (size_t i = 0; i < positions.size(); ++i)
    weld[i] = ids.emplace(std::make_tuple(positions[i].x, positions[i].y, positions[i].z),
                          static_cast<uint32_t>(ids.size())).first->second;
  Topology t;
  t.faces = indices.size() / 3;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  std::vector<uint32_t> parent(ids.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<bool> used(ids.size(), false);
  for (size_t f = 0; f < t.faces; ++f)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = weld[indices[3 * f + k]], b = weld[indices[3 * f + (k + 1) % 3]];
      used[a] = true;
      ++directed[{a, b}];
      parent[find(a)] = find(b);
    }
  std::map<std::pair<uint32_t, uint32_t>, int> undirected;
  for (const auto& [e, n] : directed) {
    undirected[{std::min(e.first, e.second), std::max(e.first, e.second)}] += n;
    if (n > 1) t.inconsistentEdges += 1;
  }
  t.edges = undirected.size();
  for (const auto& [e, n] : undirected)
    if (n != 2) ++t.boundaryOrNonManifoldEdges;
  for (uint32_t v = 0; v < used.size(); ++v)
    if (used[v]) {
      ++t.vertices;
      if (find(v) == v) ++t.components;
    }
  return t;
}

}  // namespace animorph::test
