#include "core/particles/particle_transport.h"

#include "core/particles/particle_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace animorph {

namespace {

float dist2(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = a - b;
  return glm::dot(d, d);
}

// The principal axis (largest variance) of the points of both sets, by power iteration.
glm::vec3 principalAxis(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  glm::dvec3 mean(0.0);
  for (const auto* set : {&a, &b})
    for (const glm::vec3& p : *set) mean += glm::dvec3(p);
  mean /= double(std::max<size_t>(1, a.size() + b.size()));
  glm::dmat3 cov(0.0);
  for (const auto* set : {&a, &b})
    for (const glm::vec3& p : *set) {
      const glm::dvec3 d = glm::dvec3(p) - mean;
      cov += glm::outerProduct(d, d);
    }
  glm::dvec3 v(0.577, 0.577, 0.577);
  for (int i = 0; i < 50; ++i) {
    const glm::dvec3 w = cov * v;
    const double len = glm::length(w);
    if (!(len > 0.0)) break;
    v = w / len;
  }
  return glm::vec3(v);
}

// The k nearest other points of each point (a uniform grid of about two points a cell).
std::vector<std::vector<int>> nearestNeighbours(const std::vector<glm::vec3>& pts, int k) {
  const size_t n = pts.size();
  std::vector<std::vector<int>> out(n);
  if (n < 2 || k <= 0) return out;
  glm::vec3 lo(pts[0]), hi(pts[0]);
  for (const glm::vec3& p : pts) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 ext = glm::max(hi - lo, glm::vec3(1e-6f));
  const float cell = std::max(1e-6f, std::cbrt(ext.x * ext.y * ext.z * 2.0f / float(n)));
  auto cellOf = [&](const glm::vec3& p) { return glm::ivec3(glm::floor((p - lo) / cell)); };
  auto key = [](const glm::ivec3& c) {
    return (int64_t(c.x) * 73856093) ^ (int64_t(c.y) * 19349663) ^ (int64_t(c.z) * 83492791);
  };
  std::unordered_map<int64_t, std::vector<int>> grid;
  for (size_t i = 0; i < n; ++i) grid[key(cellOf(pts[i]))].push_back(int(i));
  const glm::ivec3 cells = glm::ivec3(glm::floor(ext / cell)) + 1;
  const int maxRing = std::max({cells.x, cells.y, cells.z});
  const size_t want = std::min<size_t>(size_t(k), n - 1);
  std::vector<std::pair<float, int>> cand;
  for (size_t i = 0; i < n; ++i) {
    const glm::ivec3 c = cellOf(pts[i]);
    cand.clear();
    for (int r = 0; r <= maxRing; ++r) {
      for (int dz = -r; dz <= r; ++dz)
        for (int dy = -r; dy <= r; ++dy)
          for (int dx = -r; dx <= r; ++dx) {
            if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != r) continue;  // the ring's shell only
            auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
            if (it == grid.end()) continue;
            for (int j : it->second)
              if (j != int(i)) cand.push_back({dist2(pts[i], pts[size_t(j)]), j});
          }
      // Points beyond ring r are at least r cells away: done once the k-th found is nearer.
      if (cand.size() >= want) {
        std::nth_element(cand.begin(), cand.begin() + long(want) - 1, cand.end());
        const float kth = cand[want - 1].first;
        if (kth <= float(r) * cell * float(r) * cell) break;
      }
    }
    const size_t m = std::min(want, cand.size());
    std::partial_sort(cand.begin(), cand.begin() + long(m), cand.end());
    for (size_t q = 0; q < m; ++q) out[i].push_back(cand[q].second);
  }
  return out;
}

}  // namespace

double transportCost(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to,
                     const std::vector<int>& target) {
  double c = 0.0;
  for (size_t i = 0; i < from.size() && i < target.size(); ++i) c += double(dist2(from[i], to[size_t(target[i])]));
  return c;
}

Result<ParticleTransport> assignParticles(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to,
                                          const ParticleTransportSettings& s) {
  if (from.size() != to.size())
    return Error{"particle transport: " + std::to_string(from.size()) + " particles for " + std::to_string(to.size()) +
                 " places (they must be as many)"};
  for (const auto* set : {&from, &to})
    for (const glm::vec3& p : *set)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        return Error{"particle transport: a position is not finite"};
  const size_t n = from.size();
  ParticleTransport out;
  out.target.resize(n);
  // Greedy start: rank along the principal axis to rank.
  const glm::vec3 axis = principalAxis(from, to);
  auto order = [&](const std::vector<glm::vec3>& pts) {
    std::vector<int> idx(n);
    std::iota(idx.begin(), idx.end(), 0);
    std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) {
      return glm::dot(pts[size_t(a)], axis) < glm::dot(pts[size_t(b)], axis);
    });
    return idx;
  };
  const std::vector<int> fa = order(from), ta = order(to);
  for (size_t r = 0; r < n; ++r) out.target[size_t(fa[r])] = ta[r];
  out.report.greedyCost = transportCost(from, to, out.target);
  // Exchanges among neighbours until none shortens the sum.
  const std::vector<std::vector<int>> near = nearestNeighbours(from, s.neighbours);
  for (int sweep = 0; sweep < s.maxSweeps; ++sweep) {
    if (s.cancel && s.cancel->load()) {
      out.report.cancelled = true;
      break;
    }
    size_t changed = 0;
    for (size_t i = 0; i < n; ++i)
      for (int j : near[i]) {
        int& ti = out.target[i];
        int& tj = out.target[size_t(j)];
        const float now = dist2(from[i], to[size_t(ti)]) + dist2(from[size_t(j)], to[size_t(tj)]);
        const float swapped = dist2(from[i], to[size_t(tj)]) + dist2(from[size_t(j)], to[size_t(ti)]);
        if (swapped < now * (1.0f - 1e-6f)) {
          std::swap(ti, tj);
          ++changed;
        }
      }
    out.report.sweeps = sweep + 1;
    out.report.exchanges += changed;
    if (changed == 0) break;
  }
  out.report.cost = transportCost(from, to, out.target);
  return out;
}

Result<BlobTree> reformedParticles(const BlobTree& particles, const std::vector<glm::vec3>& places,
                                   const std::vector<int>& target) {
  BlobTree out = particles;
  size_t count = 0;
  forEachParticleNode(out.root, [&](BlobNode&) { ++count; });
  if (count != target.size() || count != places.size())
    return Error{"particle transport: the tree has " + std::to_string(count) + " particles, the assignment " +
                 std::to_string(target.size()) + " and the shape " + std::to_string(places.size()) + " places"};
  size_t i = 0;
  forEachParticleNode(out.root, [&](BlobNode& n) { n.vec3Param("center") = Vec3Track(places[size_t(target[i++])]); });
  return out;
}

Result<std::vector<glm::vec3>> particlePlaces(const FieldProgram& shape, size_t n, ConvertToParticlesSettings s) {
  if (n == 0) return Error{"particle transport: no particles to place"};
  s.count = int(n);
  for (int attempt = 0; attempt < 6; ++attempt) {
    auto conv = convertToParticles(shape, s);
    if (!conv) return Error{conv.error()};
    if (conv->report.cancelled) return Error{"particle transport: cancelled"};
    TreeParticles tp = treeParticles(conv->tree, 0.0);
    const std::vector<glm::vec3>& all = tp.set.position;
    if (all.size() >= n) {
      std::vector<glm::vec3> out(n);
      for (size_t i = 0; i < n; ++i) out[i] = all[i * all.size() / n];  // evenly thinned
      return out;
    }
    s.count = int(double(s.count) * double(n) / double(std::max<size_t>(1, all.size())) * 1.02) + 1;
  }
  return Error{"particle transport: the shape does not hold " + std::to_string(n) + " particles"};
}

Result<BlobTree> reformIntoShape(const BlobTree& particles, double timeSec, const FieldProgram& shape,
                                 const ConvertToParticlesSettings& places, const ParticleTransportSettings& transport,
                                 ParticleTransportReport* report) {
  TreeParticles tp = treeParticles(particles, timeSec);
  if (tp.nodeIds.empty()) return Error{"particle transport: the tree has no point primitive"};
  auto to = particlePlaces(shape, tp.nodeIds.size(), places);
  if (!to) return Error{to.error()};
  auto assigned = assignParticles(tp.set.position, *to, transport);
  if (!assigned) return Error{assigned.error()};
  if (assigned->report.cancelled) return Error{"particle transport: cancelled"};
  if (report) *report = assigned->report;
  return reformedParticles(particles, *to, assigned->target);
}

}  // namespace animorph
