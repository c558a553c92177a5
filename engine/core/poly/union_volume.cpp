#include "core/poly/union_volume.h"

#include <algorithm>
#include <cmath>

namespace animorph {

namespace {

struct Crossing {
  float x;
  int shell;
  int delta;  // +1 entering (the triangle faces -x), -1 leaving
};

}  // namespace

double unionVolume(const TriangleMesh& mesh, const std::vector<size_t>& firstTriangle, int columns) {
  const size_t triangles = mesh.triangleCount();
  if (triangles == 0 || columns < 1) return 0.0;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (uint32_t i : mesh.indices) {
    lo = glm::min(lo, mesh.positions[i]);
    hi = glm::max(hi, mesh.positions[i]);
  }
  // Square columns over y-z; their centres are offset by an irrational fraction
  // of a cell so that rays do not run exactly through the polygonisers' grid vertices.
  const float cell = std::max(hi.y - lo.y, hi.z - lo.z) / float(columns);
  if (!(cell > 0.0f)) return 0.0;
  const int ny = std::max(1, int(std::ceil((hi.y - lo.y) / cell))), nz = std::max(1, int(std::ceil((hi.z - lo.z) / cell)));
  const float oy = 0.4142136f, oz = 0.7320508f;
  auto centreY = [&](int j) { return lo.y + (float(j) + oy) * cell; };
  auto centreZ = [&](int k) { return lo.z + (float(k) + oz) * cell; };
  std::vector<std::vector<Crossing>> rays(size_t(ny) * size_t(nz));
  std::vector<size_t> starts = firstTriangle.empty() ? std::vector<size_t>{0} : firstTriangle;
  int shells = int(starts.size());
  starts.push_back(triangles);
  for (int s = 0; s < shells; ++s)
    for (size_t t = starts[size_t(s)]; t < std::min(starts[size_t(s) + 1], triangles); ++t) {
      const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                      c = mesh.positions[mesh.indices[3 * t + 2]];
      // Twice the signed area of the triangle projected on y-z: its normal's x.
      const float nx = (b.y - a.y) * (c.z - a.z) - (b.z - a.z) * (c.y - a.y);
      if (nx == 0.0f) continue;
      const int j0 = std::max(0, int(std::floor((std::min({a.y, b.y, c.y}) - lo.y) / cell - oy))),
                j1 = std::min(ny - 1, int(std::ceil((std::max({a.y, b.y, c.y}) - lo.y) / cell - oy)));
      const int k0 = std::max(0, int(std::floor((std::min({a.z, b.z, c.z}) - lo.z) / cell - oz))),
                k1 = std::min(nz - 1, int(std::ceil((std::max({a.z, b.z, c.z}) - lo.z) / cell - oz)));
      for (int j = j0; j <= j1; ++j)
        for (int k = k0; k <= k1; ++k) {
          const float y = centreY(j), z = centreZ(k);
          // Barycentric coordinates in the y-z projection.
          const float wa = ((b.y - y) * (c.z - z) - (b.z - z) * (c.y - y)) / nx;
          const float wb = ((c.y - y) * (a.z - z) - (c.z - z) * (a.y - y)) / nx;
          const float wc = 1.0f - wa - wb;
          if (wa < 0.0f || wb < 0.0f || wc < 0.0f) continue;
          rays[size_t(j) * size_t(nz) + size_t(k)].push_back({wa * a.x + wb * b.x + wc * c.x, s, nx < 0.0f ? 1 : -1});
        }
    }
  double length = 0.0;
  std::vector<int> winding(size_t(shells), 0);
  for (std::vector<Crossing>& r : rays) {
    if (r.empty()) continue;
    std::sort(r.begin(), r.end(), [](const Crossing& p, const Crossing& q) { return p.x < q.x; });
    std::fill(winding.begin(), winding.end(), 0);
    int insideShells = 0;  // shells with winding >= 1 here
    float enteredAt = 0.0f;
    for (const Crossing& c : r) {
      int& w = winding[size_t(c.shell)];
      const bool before = w >= 1;
      w += c.delta;
      const bool after = w >= 1;
      if (before == after) continue;
      if (after && insideShells++ == 0) enteredAt = c.x;
      if (!after && --insideShells == 0) length += double(c.x - enteredAt);
    }
  }
  return length * double(cell) * double(cell);
}

}  // namespace animorph
