#include "core/poly/mesh_checks.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace animorph {

namespace {

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

}  // namespace

MeshTopology analyzeMesh(const TriangleMesh& m) {
  MeshTopology t;
  const size_t nv = m.positions.size();
  const size_t nf = m.indices.size() / 3;
  t.faces = nf;
  std::vector<uint8_t> used(nv, 0);
  // Directed half-edges keyed by their undirected edge.
  struct Half {
    uint64_t key;
    bool forward;
  };
  std::vector<Half> halves;
  halves.reserve(nf * 3);
  for (size_t f = 0; f < nf; ++f) {
    uint32_t v[3] = {m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
    if (v[0] >= nv || v[1] >= nv || v[2] >= nv || v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
      ++t.degenerateTriangles;
      continue;
    }
    glm::dvec3 a(m.positions[v[0]]), b(m.positions[v[1]]), c(m.positions[v[2]]);
    if (glm::length(glm::cross(b - a, c - a)) <= 0.0) ++t.degenerateTriangles;
    for (int k = 0; k < 3; ++k) {
      used[v[k]] = 1;
      uint32_t p = v[k], q = v[(k + 1) % 3];
      halves.push_back({(uint64_t(std::min(p, q)) << 32) | std::max(p, q), p < q});
    }
  }
  std::sort(halves.begin(), halves.end(), [](const Half& a, const Half& b) { return a.key < b.key; });
  for (size_t i = 0; i < halves.size();) {
    size_t j = i;
    int fwd = 0;
    while (j < halves.size() && halves[j].key == halves[i].key) fwd += halves[j++].forward;
    size_t n = j - i;
    ++t.edges;
    if (n == 1) ++t.boundaryEdges;
    else if (n > 2) ++t.nonManifoldEdges;
    else if (fwd != 1) ++t.misorientedEdges;
    i = j;
  }
  for (uint8_t u : used) t.vertices += u;
  t.euler = (long long)t.vertices - (long long)t.edges + (long long)t.faces;

  // Components through shared edges.
  UnionFind uf(nv);
  for (size_t f = 0; f < nf; ++f) {
    uint32_t a = m.indices[3 * f], b = m.indices[3 * f + 1], c = m.indices[3 * f + 2];
    if (a >= nv || b >= nv || c >= nv) continue;
    uf.unite(a, b);
    uf.unite(b, c);
  }
  for (uint32_t v = 0; v < nv; ++v)
    if (used[v] && uf.find(v) == v) ++t.components;

  // Vertex links: each vertex's opposite edges must form exactly one cycle.
  std::vector<uint32_t> start(nv + 1, 0);
  for (size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (m.indices[3 * f + k] < nv) ++start[m.indices[3 * f + k] + 1];
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<uint32_t> incident(start[nv]);
  for (size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (m.indices[3 * f + k] < nv) incident[fill[m.indices[3 * f + k]]++] = uint32_t(f);
  std::vector<std::pair<uint32_t, uint32_t>> link;
  std::vector<uint32_t> verts;
  for (uint32_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    link.clear();
    verts.clear();
    for (uint32_t i = start[v]; i < start[v + 1]; ++i) {
      uint32_t f = incident[i];
      uint32_t a = m.indices[3 * f], b = m.indices[3 * f + 1], c = m.indices[3 * f + 2];
      uint32_t p, q;
      if (a == v) { p = b; q = c; }
      else if (b == v) { p = c; q = a; }
      else { p = a; q = b; }
      link.push_back({p, q});
      verts.push_back(p);
      verts.push_back(q);
    }
    std::sort(verts.begin(), verts.end());
    // Closed fan: every link vertex appears exactly twice, and the link is connected.
    bool ok = true;
    for (size_t i = 0; i < verts.size(); i += 2)
      if (i + 1 >= verts.size() || verts[i] != verts[i + 1] || (i + 2 < verts.size() && verts[i + 2] == verts[i])) {
        ok = false;
        break;
      }
    if (ok) {
      // Walk the cycle: it must visit every link edge.
      size_t steps = 0;
      uint32_t cur = link[0].second;
      size_t guard = link.size() + 1;
      while (steps < guard) {
        ++steps;
        if (cur == link[0].first) break;
        auto it = std::find_if(link.begin(), link.end(), [&](auto& e) { return e.first == cur; });
        if (it == link.end()) {
          ok = false;
          break;
        }
        cur = it->second;
      }
      if (steps != link.size()) ok = false;
    }
    if (!ok) ++t.nonManifoldVertices;
  }
  return t;
}

double meshVolume(const TriangleMesh& m) {
  double v = 0.0;
  for (size_t f = 0; f + 2 < m.indices.size(); f += 3) {
    glm::dvec3 a(m.positions[m.indices[f]]), b(m.positions[m.indices[f + 1]]), c(m.positions[m.indices[f + 2]]);
    v += glm::dot(a, glm::cross(b, c));
  }
  return v / 6.0;
}
}  // namespace animorph
