#include "core/particles/mesh_inside.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/poly/mesh_checks.h"

namespace animorph {

namespace {

struct PositionKey {
  uint32_t bits[3];
  bool operator==(const PositionKey& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};
struct PositionHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = 1469598103934665603ull;
    for (uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return size_t(h);
  }
};

// One triangle's crossing of a column's ray: where along the axis, and +1 / -1 as the triangle
// faces along the axis or against it.
struct Crossing {
  float at;
  int sign;
};

// 2D cross product of a and b (coordinates relative to the column).
double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// Whether the column (the origin) is on the inner side of edge p0 -> p1 of a counter-clockwise
// triangle (w: cross2(p0, p1)), a point exactly on the edge counting for the triangle on one side
// only (the edge's direction decides; the triangle across runs it the other way).
bool onInnerSide(double w, const glm::dvec2& p0, const glm::dvec2& p1) {
  if (w != 0.0) return w > 0.0;
  const glm::dvec2 d = p1 - p0;
  return d.y < 0.0 || (d.y == 0.0 && d.x > 0.0);
}

}  // namespace

MeshInside::MeshInside(const TriangleMesh& mesh) {
  TriangleMesh welded;
  std::unordered_map<PositionKey, uint32_t, PositionHash> index;
  std::vector<uint32_t> remap(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = mesh.positions[i] + glm::vec3(0.0f);  // -0 welds with +0
    PositionKey k;
    std::memcpy(k.bits, &p.x, sizeof k.bits);
    auto [it, added] = index.emplace(k, uint32_t(welded.positions.size()));
    if (added) welded.positions.push_back(p);
    remap[i] = it->second;
  }
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    glm::uvec3 tri;
    bool valid = true;
    for (int c = 0; c < 3; ++c) {
      const uint32_t i = mesh.indices[t + size_t(c)];
      valid = valid && i < remap.size();
      tri[c] = valid ? remap[i] : 0;
    }
    if (!valid || tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) continue;
    welded.indices.insert(welded.indices.end(), {tri.x, tri.y, tri.z});
    triangles_.push_back(tri);
  }
  info_.triangles = triangles_.size();
  info_.boundaryEdges = analyzeMesh(welded).boundaryEdges;
  info_.volume = std::abs(meshVolume(welded));
  for (const glm::uvec3& t : triangles_)
    for (int c = 0; c < 3; ++c) info_.bounds.add(welded.positions[t[c]]);
  positions_ = std::move(welded.positions);
}

std::vector<uint8_t> MeshInside::windingAlong(int axis, const SampleLattice& g) const {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) is right-handed
  const int nu = g.dims[u], nv = g.dims[v], nw = g.dims[axis];
  auto columnCoord = [&](int c, int i) { return g.origin[c] + g.spacing * float(i); };
  // Column c = iu + nu iv lists the triangles whose projected box spans it (one column more on
  // each side, so that rounding never drops a triangle whose edge runs through the column).
  auto span = [&](int c, float lo, float hi, int n, int& a, int& b) {
    a = std::max(0, int(std::floor((lo - g.origin[c]) / g.spacing)) - 1);
    b = std::min(n - 1, int(std::ceil((hi - g.origin[c]) / g.spacing)) + 1);
  };
  const size_t columns = size_t(nu) * size_t(nv);
  std::vector<uint32_t> first(columns + 1, 0);
  std::vector<glm::ivec4> spans(triangles_.size());
  for (size_t t = 0; t < triangles_.size(); ++t) {
    const glm::vec3 &a = positions_[triangles_[t].x], &b = positions_[triangles_[t].y], &c = positions_[triangles_[t].z];
    glm::ivec4& s = spans[t];
    span(u, std::min({a[u], b[u], c[u]}), std::max({a[u], b[u], c[u]}), nu, s.x, s.y);
    span(v, std::min({a[v], b[v], c[v]}), std::max({a[v], b[v], c[v]}), nv, s.z, s.w);
    for (int j = s.z; j <= s.w; ++j)
      for (int i = s.x; i <= s.y; ++i) ++first[size_t(i) + size_t(nu) * size_t(j) + 1];
  }
  for (size_t c = 0; c < columns; ++c) first[c + 1] += first[c];
  std::vector<uint32_t> list(first.back());
  {
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t t = 0; t < triangles_.size(); ++t) {
      const glm::ivec4& s = spans[t];
      for (int j = s.z; j <= s.w; ++j)
        for (int i = s.x; i <= s.y; ++i) list[fill[size_t(i) + size_t(nu) * size_t(j)]++] = uint32_t(t);
    }
  }
  std::vector<uint8_t> inside(g.size(), 0);
  tbb::enumerable_thread_specific<std::vector<Crossing>> scratch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, columns), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<Crossing>& crossings = scratch.local();
    for (size_t col = r.begin(); col != r.end(); ++col) {
      const int iu = int(col % size_t(nu)), iv = int(col / size_t(nu));
      const double pu = columnCoord(u, iu), pv = columnCoord(v, iv);
      crossings.clear();
      for (uint32_t k = first[col]; k < first[col + 1]; ++k) {
        const glm::uvec3& tri = triangles_[list[k]];
        glm::dvec2 p[3];
        float w[3];
        for (int c = 0; c < 3; ++c) {
          const glm::vec3& q = positions_[tri[c]];
          p[c] = glm::dvec2(double(q[u]) - pu, double(q[v]) - pv);
          w[c] = q[axis];
        }
        const double area = cross2(p[1] - p[0], p[2] - p[0]);
        if (area == 0.0) continue;  // seen edge-on: its neighbours' shared edges decide
        if (area < 0.0) {           // make it counter-clockwise
          std::swap(p[1], p[2]);
          std::swap(w[1], w[2]);
        }
        const double b0 = cross2(p[1], p[2]), b1 = cross2(p[2], p[0]), b2 = cross2(p[0], p[1]);
        if (!onInnerSide(b0, p[1], p[2]) || !onInnerSide(b1, p[2], p[0]) || !onInnerSide(b2, p[0], p[1])) continue;
        const double at = (b0 * w[0] + b1 * w[1] + b2 * w[2]) / (b0 + b1 + b2);
        crossings.push_back({float(at), area > 0.0 ? 1 : -1});
      }
      if (crossings.empty()) continue;
      std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) { return a.at < b.at; });
      int winding = 0;  // of the crossings past the point, along +axis
      for (const Crossing& c : crossings) winding += c.sign;
      size_t next = 0;
      glm::ivec3 idx;
      idx[u] = iu;
      idx[v] = iv;
      for (int k = 0; k < nw; ++k) {
        const float at = columnCoord(axis, k);
        while (next < crossings.size() && crossings[next].at <= at) winding -= crossings[next++].sign;
        idx[axis] = k;
        inside[g.index(idx.x, idx.y, idx.z)] = winding != 0;
      }
    }
  });
  return inside;
}

std::vector<uint8_t> MeshInside::insideOnLattice(const SampleLattice& lattice) const {
  std::vector<uint8_t> inside = windingAlong(2, lattice);
  if (closed()) return inside;
  const std::vector<uint8_t> alongX = windingAlong(0, lattice), alongY = windingAlong(1, lattice);
  for (size_t i = 0; i < inside.size(); ++i) inside[i] = inside[i] + alongX[i] + alongY[i] >= 2;
  return inside;
}

Result<ParticleShape> meshParticleShape(const MeshInside& mesh) {
  const MeshInsideInfo& info = mesh.info();
  if (info.triangles == 0) return Error{"convert to particles: the mesh has no triangle"};
  const glm::vec3 size = info.bounds.size();
  if (std::min({size.x, size.y, size.z}) <= 1e-6f * info.bounds.diagonal()) {
    char box[96];
    std::snprintf(box, sizeof box, "%.3g x %.3g x %.3g m", double(size.x), double(size.y), double(size.z));
    return Error{std::string("convert to particles: the mesh is flat (its box is ") + box +
                 "): it encloses no volume"};
  }
  ParticleShape shape;
  shape.bounds = mesh.info().bounds;
  shape.insideOnLattice = [&mesh](const SampleLattice& g) { return mesh.insideOnLattice(g); };
  return shape;
}

}  // namespace animorph
