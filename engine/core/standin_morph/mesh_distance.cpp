#include "core/standin_morph/mesh_distance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/field/skeleton.h"
#include "core/math/bounds.h"

namespace animorph {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The mesh's triangles bucketed in a uniform grid over its box, about two triangles per cell on
// average over the surface; a triangle is listed in every cell its bounding box overlaps.
class TriangleGrid {
 public:
  explicit TriangleGrid(const TriangleMesh& mesh) : mesh_(mesh) {
    for (const auto& p : mesh.positions) box_.add(p);
    const size_t nt = mesh.triangleCount();
    const glm::vec3 size = glm::max(box_.size(), glm::vec3(1e-6f));
    const float cell = std::max(1e-6f, std::cbrt(size.x * size.y * size.z / float(std::max<size_t>(1, nt / 2))));
    dims_ = glm::clamp(glm::ivec3(glm::ceil(size / cell)) + 1, glm::ivec3(1), glm::ivec3(256));
    cs_ = size / glm::vec3(dims_) * 1.0001f;
    buckets_.resize(size_t(dims_.x) * size_t(dims_.y) * size_t(dims_.z));
    for (size_t t = 0; t < nt; ++t) {
      const glm::vec3 &a = corner(t, 0), &b = corner(t, 1), &c = corner(t, 2);
      const glm::ivec3 lo = cellOf(glm::min(a, glm::min(b, c))), hi = cellOf(glm::max(a, glm::max(b, c)));
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) buckets_[at(x, y, z)].push_back(uint32_t(t));
    }
  }

  // Distance from p to the closest triangle, searched ring by ring of cells around p's cell. As
  // soon as a triangle within stopAt is found, returns that triangle's distance (<= stopAt) without
  // looking further: a caller after the largest distance over many points passes the largest so
  // far, and a point that cannot raise it costs a few triangles. stopAt < 0: always exact.
  float distance(const glm::vec3& p, float stopAt) const {
    const glm::ivec3 c0 = cellOf(p);
    const int maxRing = std::max(dims_.x, std::max(dims_.y, dims_.z));
    float best = kInf;
    for (int ring = 0; ring <= maxRing; ++ring) {
      if (searchRing(p, c0, ring, stopAt, best)) return best;
      // Every triangle not seen yet lies in cells outside this ring's box of cells.
      if (best <= distanceOutOfRing(p, c0, ring)) break;
    }
    return best;
  }

 private:
  const glm::vec3& corner(size_t t, int k) const { return mesh_.positions[mesh_.indices[3 * t + size_t(k)]]; }
  glm::ivec3 cellOf(const glm::vec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor((p - box_.min) / cs_)), glm::ivec3(0), dims_ - 1);
  }
  size_t at(int x, int y, int z) const {
    return (size_t(z) * size_t(dims_.y) + size_t(y)) * size_t(dims_.x) + size_t(x);
  }

  // The triangles of the cells at Chebyshev distance ring from c0 (inside the grid) lower best.
  // Returns true once best <= stopAt.
  bool searchRing(const glm::vec3& p, const glm::ivec3& c0, int ring, float stopAt, float& best) const {
    const glm::ivec3 lo = glm::max(c0 - ring, glm::ivec3(0)), hi = glm::min(c0 + ring, dims_ - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          if (std::max(std::abs(x - c0.x), std::max(std::abs(y - c0.y), std::abs(z - c0.z))) != ring) continue;
          for (uint32_t t : buckets_[at(x, y, z)]) {
            best = std::min(best, glm::length(p - closestOnTriangle(p, corner(t, 0), corner(t, 1), corner(t, 2))));
            if (best <= stopAt) return true;
          }
        }
    return false;
  }

  // The distance from p (anywhere) to the nearest cell outside the cells within ring of c0: to the
  // nearest of the slabs of the grid beyond that box of cells (infinite when it covers the grid).
  float distanceOutOfRing(const glm::vec3& p, const glm::ivec3& c0, int ring) const {
    const glm::vec3 gridMax = box_.min + glm::vec3(dims_) * cs_;
    auto toBox = [&](const glm::vec3& lo, const glm::vec3& hi) {
      return glm::length(glm::max(glm::vec3(0.0f), glm::max(lo - p, p - hi)));
    };
    float d = kInf;
    for (int a = 0; a < 3; ++a) {
      if (c0[a] - ring > 0) {
        glm::vec3 hi = gridMax;
        hi[a] = box_.min[a] + float(c0[a] - ring) * cs_[a];
        d = std::min(d, toBox(box_.min, hi));
      }
      if (c0[a] + ring < dims_[a] - 1) {
        glm::vec3 lo = box_.min;
        lo[a] = box_.min[a] + float(c0[a] + ring + 1) * cs_[a];
        d = std::min(d, toBox(lo, gridMax));
      }
    }
    return d;
  }

  const TriangleMesh& mesh_;
  Bounds box_;
  glm::ivec3 dims_{1};
  glm::vec3 cs_{1.0f};
  std::vector<std::vector<uint32_t>> buckets_;
};

}  // namespace

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
  if (mesh.triangleCount() == 0) return std::vector<float>(points.size(), kInf);
  const TriangleGrid grid(mesh);
  std::vector<float> dist(points.size());
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) { dist[i] = grid.distance(points[i], -1.0f); });
  return dist;
}

double maxPointToMeshDistance(const std::vector<glm::vec3>& points, const TriangleMesh& mesh) {
  if (points.empty()) return 0.0;
  if (mesh.triangleCount() == 0) return double(kInf);
  const TriangleGrid grid(mesh);
  std::atomic<float> largest{0.0f};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    float local = largest.load(std::memory_order_relaxed);
    for (size_t i = r.begin(); i < r.end(); ++i) {
      local = std::max(local, largest.load(std::memory_order_relaxed));
      // A point within the largest distance so far cannot raise it: the search stops at the first
      // triangle that close. A farther point is searched in full, so the result is exact.
      const float d = grid.distance(points[i], local);
      if (d <= local) continue;
      local = d;
      float seen = largest.load(std::memory_order_relaxed);
      while (seen < d && !largest.compare_exchange_weak(seen, d, std::memory_order_relaxed)) {
      }
    }
  });
  return double(largest.load());
}

}  // namespace animorph
