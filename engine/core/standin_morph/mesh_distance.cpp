#include "core/standin_morph/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/field/skeleton.h"
#include "core/math/bounds.h"

namespace animorph {

PointMeshDistances pointsToMeshDistance(const std::vector<glm::vec3>& points, const TriangleMesh& mesh) {
  PointMeshDistances r;
  r.points = points.size();
  if (points.empty()) return r;
  const std::vector<float> dist = pointDistancesToMesh(points, mesh);
  double sum = 0.0;
  for (float d : dist) {
    sum += double(d);
    r.maxDistance = std::max(r.maxDistance, double(d));
  }
  r.meanDistance = sum / double(dist.size());
  return r;
}

std::vector<float> pointDistancesToMesh(const std::vector<glm::vec3>& points, const TriangleMesh& mesh) {
  const size_t nt = mesh.triangleCount();
  if (nt == 0) return std::vector<float>(points.size(), std::numeric_limits<float>::infinity());
  Bounds box;
  for (const auto& p : mesh.positions) box.add(p);
  // About two triangles per cell on average over the surface.
  const glm::vec3 size = glm::max(box.size(), glm::vec3(1e-6f));
  const float cell = std::max(1e-6f, std::cbrt(size.x * size.y * size.z / float(std::max<size_t>(1, nt / 2))));
  const glm::ivec3 dims = glm::clamp(glm::ivec3(glm::ceil(size / cell)) + 1, glm::ivec3(1), glm::ivec3(256));
  const glm::vec3 cs = size / glm::vec3(dims) * 1.0001f;
  auto cellOf = [&](const glm::vec3& p) {
    return glm::clamp(glm::ivec3(glm::floor((p - box.min) / cs)), glm::ivec3(0), dims - 1);
  };
  const size_t ncell = size_t(dims.x) * size_t(dims.y) * size_t(dims.z);
  std::vector<std::vector<uint32_t>> buckets(ncell);
  auto at = [&](int x, int y, int z) { return (size_t(z) * size_t(dims.y) + size_t(y)) * size_t(dims.x) + size_t(x); };
  for (size_t t = 0; t < nt; ++t) {
    const glm::vec3& a = mesh.positions[mesh.indices[3 * t]];
    const glm::vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
    const glm::vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
    const glm::ivec3 lo = cellOf(glm::min(a, glm::min(b, c))), hi = cellOf(glm::max(a, glm::max(b, c)));
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) buckets[at(x, y, z)].push_back(uint32_t(t));
  }
  const float minCs = std::min(cs.x, std::min(cs.y, cs.z));
  std::vector<float> dist(points.size());
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    const glm::vec3 p = points[i];
    // Distance from p to the grid box (points may lie outside it).
    const glm::vec3 outside = glm::max(glm::vec3(0.0f), glm::max(box.min - p, p - box.max));
    const float base = glm::length(outside);
    const glm::ivec3 c0 = cellOf(p);
    float best = std::numeric_limits<float>::max();
    const int maxRing = std::max(dims.x, std::max(dims.y, dims.z));
    for (int ring = 0; ring <= maxRing; ++ring) {
      for (int z = c0.z - ring; z <= c0.z + ring; ++z)
        for (int y = c0.y - ring; y <= c0.y + ring; ++y)
          for (int x = c0.x - ring; x <= c0.x + ring; ++x) {
            if (std::max(std::abs(x - c0.x), std::max(std::abs(y - c0.y), std::abs(z - c0.z))) != ring) continue;
            if (x < 0 || y < 0 || z < 0 || x >= dims.x || y >= dims.y || z >= dims.z) continue;
            for (uint32_t t : buckets[at(x, y, z)]) {
              const glm::vec3 q = closestOnTriangle(p, mesh.positions[mesh.indices[3 * t]],
                                                    mesh.positions[mesh.indices[3 * t + 1]],
                                                    mesh.positions[mesh.indices[3 * t + 2]]);
              best = std::min(best, glm::length(p - q));
            }
          }
      // Cells beyond this ring are at least ring * cell away (plus the box gap).
      if (best <= base + float(ring) * minCs) break;
    }
    dist[i] = best;
  });
  return dist;
}

}  // namespace animorph
