#include "core/poly/inside_mesh.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace animorph {

namespace {

// Triangles bucketed on a grid over the plane across one axis (the rays run along it).
struct RayGrid {
  int axis = 0, u = 1, v = 2;  // ray axis and the plane's two axes
  glm::vec2 lo{0.0f}, cell{1.0f};
  glm::ivec2 dims{1, 1};
  std::vector<std::vector<uint32_t>> buckets;

  glm::ivec2 cellOf(float a, float b) const {
    return glm::clamp(glm::ivec2(int(std::floor((a - lo.x) / cell.x)), int(std::floor((b - lo.y) / cell.y))),
                      glm::ivec2(0), dims - 1);
  }
};

RayGrid buildGrid(const TriangleMesh& m, int axis) {
  RayGrid g;
  g.axis = axis;
  g.u = (axis + 1) % 3;
  g.v = (axis + 2) % 3;
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : m.positions) {
    lo = glm::min(lo, glm::vec2(p[g.u], p[g.v]));
    hi = glm::max(hi, glm::vec2(p[g.u], p[g.v]));
  }
  const size_t nt = m.triangleCount();
  // About four triangles per bucket over the projected area (most buckets see two layers).
  const int side = std::clamp(int(std::sqrt(double(nt) / 2.0)), 1, 512);
  g.lo = lo;
  g.dims = glm::ivec2(side);
  g.cell = glm::max((hi - lo) / float(side), glm::vec2(1e-7f)) * 1.0001f;
  g.buckets.resize(size_t(side) * size_t(side));
  for (size_t t = 0; t < nt; ++t) {
    const glm::vec3 &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]],
                    &c = m.positions[m.indices[3 * t + 2]];
    const glm::ivec2 c0 = g.cellOf(std::min({a[g.u], b[g.u], c[g.u]}), std::min({a[g.v], b[g.v], c[g.v]}));
    const glm::ivec2 c1 = g.cellOf(std::max({a[g.u], b[g.u], c[g.u]}), std::max({a[g.v], b[g.v], c[g.v]}));
    for (int j = c0.y; j <= c1.y; ++j)
      for (int i = c0.x; i <= c1.x; ++i) g.buckets[size_t(j) * size_t(side) + size_t(i)].push_back(uint32_t(t));
  }
  return g;
}

// Winding number of mesh around p along the ray p + s e_axis, s > 0: +1 for each triangle the ray
// leaves through (facing +axis), -1 for each it enters through.
int windingAlongRay(const TriangleMesh& m, const RayGrid& g, const glm::vec3& p) {
  const float pu = p[g.u], pv = p[g.v];
  if (pu < g.lo.x || pv < g.lo.y || pu > g.lo.x + g.cell.x * float(g.dims.x) || pv > g.lo.y + g.cell.y * float(g.dims.y))
    return 0;
  const glm::ivec2 c = g.cellOf(pu, pv);
  int w = 0;
  for (uint32_t t : g.buckets[size_t(c.y) * size_t(g.dims.x) + size_t(c.x)]) {
    const glm::vec3 &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]],
                    &d = m.positions[m.indices[3 * t + 2]];
    // Twice the signed area of the projection: the normal's component along the ray.
    const float n = (b[g.u] - a[g.u]) * (d[g.v] - a[g.v]) - (b[g.v] - a[g.v]) * (d[g.u] - a[g.u]);
    if (n == 0.0f) continue;
    const float wa = ((b[g.u] - pu) * (d[g.v] - pv) - (b[g.v] - pv) * (d[g.u] - pu)) / n;
    const float wb = ((d[g.u] - pu) * (a[g.v] - pv) - (d[g.v] - pv) * (a[g.u] - pu)) / n;
    const float wc = 1.0f - wa - wb;
    // Half-open on one side so that a ray through a shared edge counts it once.
    if (wa < 0.0f || wb < 0.0f || wc <= 0.0f) continue;
    const float s = wa * a[g.axis] + wb * b[g.axis] + wc * d[g.axis];
    if (s <= p[g.axis]) continue;
    w += n > 0.0f ? 1 : -1;
  }
  return w;
}

}  // namespace

std::vector<uint8_t> pointsInsideMesh(const std::vector<glm::vec3>& points, const TriangleMesh& mesh) {
  std::vector<uint8_t> inside(points.size(), 0);
  if (mesh.triangleCount() == 0 || points.empty()) return inside;
  const RayGrid grids[3] = {buildGrid(mesh, 0), buildGrid(mesh, 1), buildGrid(mesh, 2)};
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    int votes = 0;
    for (const RayGrid& g : grids) votes += windingAlongRay(mesh, g, points[i]) >= 1;
    inside[i] = votes >= 2;
  });
  return inside;
}

}  // namespace animorph
