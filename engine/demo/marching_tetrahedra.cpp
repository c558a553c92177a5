#include "demo/marching_tetrahedra.h"

#include <cmath>
#include <unordered_map>

namespace animorph {

TriangleMesh marchingTetrahedra(const std::function<float(const glm::vec3&)>& f, const Bounds& box, float cellSize) {
  TriangleMesh out;
  if (box.empty() || !(cellSize > 0.0f)) return out;
  const glm::ivec3 cells = glm::max(glm::ivec3(glm::ceil(box.size() / cellSize)), glm::ivec3(1));
  const glm::ivec3 pts = cells + 1;
  const size_t nx = pts.x, ny = pts.y, nz = pts.z;
  auto gridIndex = [&](int x, int y, int z) { return (static_cast<size_t>(z) * ny + y) * nx + x; };
  auto gridPoint = [&](size_t g) {
    int x = static_cast<int>(g % nx), y = static_cast<int>((g / nx) % ny), z = static_cast<int>(g / (nx * ny));
    return box.min + glm::vec3(x, y, z) * cellSize;
  };
  std::vector<float> value(nx * ny * nz);
  for (size_t g = 0; g < value.size(); ++g) {
    float v = f(gridPoint(g));
    // Exact zeros would create degenerate vertices: nudge them outside.
    value[g] = v == 0.0f ? -1e-12f : v;
  }
  std::unordered_map<uint64_t, uint32_t> edgeVertex;
  edgeVertex.reserve(value.size() / 4);
  auto vertexOn = [&](size_t a, size_t b) {
    if (a > b) std::swap(a, b);
    const uint64_t key = static_cast<uint64_t>(a) * value.size() + b;
    auto it = edgeVertex.find(key);
    if (it != edgeVertex.end()) return it->second;
    const float fa = value[a], fb = value[b];
    const float t = fa / (fa - fb);
    out.positions.push_back(glm::mix(gridPoint(a), gridPoint(b), t));
    const auto id = static_cast<uint32_t>(out.positions.size() - 1);
    edgeVertex.emplace(key, id);
    return id;
  };
  auto emit = [&](uint32_t a, uint32_t b, uint32_t c, const glm::vec3& outward) {
    glm::vec3 n = glm::cross(out.positions[b] - out.positions[a], out.positions[c] - out.positions[a]);
    if (glm::dot(n, outward) < 0.0f) std::swap(b, c);
    out.indices.insert(out.indices.end(), {a, b, c});
  };
  // Six tetrahedra 0 -> e_a -> e_a + e_b -> 7 for every axis order (a, b).
  static const int kPaths[6][2] = {{1, 2}, {1, 4}, {2, 1}, {2, 4}, {4, 1}, {4, 2}};
  for (int z = 0; z < cells.z; ++z)
    for (int y = 0; y < cells.y; ++y)
      for (int x = 0; x < cells.x; ++x) {
        size_t corner[8];
        bool anyIn = false, anyOut = false;
        for (int c = 0; c < 8; ++c) {
          corner[c] = gridIndex(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
          (value[corner[c]] > 0.0f ? anyIn : anyOut) = true;
        }
        if (!anyIn || !anyOut) continue;
        for (const auto& p : kPaths) {
          const size_t tet[4] = {corner[0], corner[p[0]], corner[p[0] | p[1]], corner[7]};
          size_t in[4], outs[4];
          int ni = 0, no = 0;
          glm::vec3 cin(0.0f), cout(0.0f);
          for (size_t g : tet) {
            if (value[g] > 0.0f) { in[ni++] = g; cin += gridPoint(g); }
            else { outs[no++] = g; cout += gridPoint(g); }
          }
          if (ni == 0 || no == 0) continue;
          const glm::vec3 outward = cout / float(no) - cin / float(ni);
          if (ni == 1) {
            emit(vertexOn(in[0], outs[0]), vertexOn(in[0], outs[1]), vertexOn(in[0], outs[2]), outward);
          } else if (ni == 3) {
            emit(vertexOn(outs[0], in[0]), vertexOn(outs[0], in[1]), vertexOn(outs[0], in[2]), outward);
          } else {
            // Quad through the four crossing edges, in cyclic order.
            uint32_t q0 = vertexOn(in[0], outs[0]), q1 = vertexOn(in[0], outs[1]);
            uint32_t q2 = vertexOn(in[1], outs[1]), q3 = vertexOn(in[1], outs[0]);
            emit(q0, q1, q2, outward);
            emit(q0, q2, q3, outward);
          }
        }
      }
  return out;
}

}  // namespace animorph
