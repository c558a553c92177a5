#include "core/standin/fit_quality.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <unordered_map>

#include "core/field/skeleton.h"
#include "core/poly/polygonizer.h"

namespace animorph {

namespace {

struct UnionFind {
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), uint32_t(0)); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
  std::vector<uint32_t> parent;
};

// Component label (0..k-1) of every vertex used by a triangle (others: -1), and k.
int labelComponents(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices, float weld,
                    std::vector<int>& label) {
  const size_t n = positions.size();
  UnionFind uf(n);
  if (weld > 0.0f) {
    std::unordered_map<uint64_t, uint32_t> first;
    first.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3 q = glm::floor(positions[i] / weld + 0.5f);
      const uint64_t key = (uint64_t(int64_t(q.x) & 0x1fffff) << 42) | (uint64_t(int64_t(q.y) & 0x1fffff) << 21) |
                           uint64_t(int64_t(q.z) & 0x1fffff);
      auto [it, inserted] = first.emplace(key, uint32_t(i));
      if (!inserted) uf.join(uint32_t(i), it->second);
    }
  }
  std::vector<char> used(n, 0);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    if (a >= n || b >= n || c >= n) continue;
    uf.join(a, b);
    uf.join(b, c);
    used[a] = used[b] = used[c] = 1;
  }
  label.assign(n, -1);
  std::unordered_map<uint32_t, int> ids;
  for (size_t i = 0; i < n; ++i)
    if (used[i]) label[i] = ids.emplace(uf.find(uint32_t(i)), int(ids.size())).first->second;
  return int(ids.size());
}

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0, double e = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d, e);
  return buf;
}

// The stand-in's polygonised components: count, largest gap from a piece to
// the others, and for each segment the piece its midpoint is closest to.
void measureComponents(const Standin& s, const std::vector<PosedSegment>& segs, int resolution, FitReport& r,
                       std::vector<int>& segmentPiece, std::vector<size_t>& pieceSize) {
  PolygonizeSettings ps;
  ps.resolution = resolution;
  ps.bounds = posedStandinBounds(segs, 0.0f);
  const auto poly = polygonize(standinProgram(s.kind, s.sharpness, segs), ps);
  if (!poly || poly->mesh.positions.empty()) {
    r.standinComponents = 0;
    return;
  }
  const TriangleMesh& m = poly->mesh;
  std::vector<int> label;
  r.standinComponents = labelComponents(m.positions, m.indices, 0.0f, label);
  pieceSize.assign(size_t(r.standinComponents), 0);
  for (int l : label)
    if (l >= 0) ++pieceSize[size_t(l)];
  segmentPiece.assign(segs.size(), -1);
  for (size_t k = 0; k < segs.size(); ++k) {
    const glm::vec3 mid = 0.5f * (segs[k].a + segs[k].b);
    float best = INFINITY;
    for (size_t i = 0; i < m.positions.size(); ++i) {
      if (label[i] < 0) continue;
      const float d = glm::length(m.positions[i] - mid);
      if (d < best) { best = d; segmentPiece[k] = label[i]; }
    }
  }
  if (r.standinComponents < 2) return;
  // Gap of a piece: its closest approach to any other piece, on vertex samples
  // (at most about 4000 in all, every piece's vertices thinned alike).
  const size_t stride = std::max<size_t>(1, m.positions.size() / 4000);
  std::vector<glm::vec3> sp;
  std::vector<int> sl;
  std::vector<size_t> seen(pieceSize.size(), 0);
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (label[i] >= 0 && seen[size_t(label[i])]++ % stride == 0) {
      sp.push_back(m.positions[i]);
      sl.push_back(label[i]);
    }
  std::vector<float> gap(pieceSize.size(), INFINITY);
  for (size_t i = 0; i < sp.size(); ++i)
    for (size_t j = i + 1; j < sp.size(); ++j)
      if (sl[i] != sl[j]) {
        const float d = glm::length(sp[i] - sp[j]);
        gap[size_t(sl[i])] = std::min(gap[size_t(sl[i])], d);
        gap[size_t(sl[j])] = std::min(gap[size_t(sl[j])], d);
      }
  for (float g : gap)
    if (std::isfinite(g)) r.largestGap = std::max(r.largestGap, double(g));
}

}  // namespace

int weldedComponents(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                     float weldTolerance) {
  std::vector<int> label;
  return labelComponents(positions, indices, weldTolerance, label);
}

FitReport measureFitQuality(const Character& c, const Standin& s, const CharacterPose& pose,
                            const ProjectionSettings& projection, const FitQualitySettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  FitReport r;
  r.segments = s.segments.size();
  r.farFraction = settings.farFraction;
  Bounds box;
  for (const auto& p : pose.positions) box.add(p);
  r.diagonal = box.diagonal();
  const double diag = std::max(1e-12, r.diagonal);
  const auto segs = poseStandin(s, pose.globals, glm::mat4(1.0f));
  const FieldProgram prog = standinProgram(s.kind, s.sharpness, segs);
  const size_t n = pose.positions.size();
  std::vector<glm::vec3> out(n);
  r.projection = projectOntoField(prog, segs, pose.positions.data(), n, out.data(), nullptr, projection);
  for (float d : r.projection.failureDistances)
    if (!(double(d) <= settings.surfaceNoiseFraction * diag)) ++r.projectionMisses;
  r.meanDistance = r.projection.meanDistance;
  r.maxDistance = r.projection.maxDistance;
  r.meanError = r.meanDistance / diag;
  r.maxError = r.maxDistance / diag;

  // Per segment: the vertices whose closest segment (capsule surface) it is.
  r.perSegment.resize(segs.size());
  const double far = settings.farFraction * diag;
  size_t farCount = 0;
  std::vector<size_t> segFar(segs.size(), 0);
  for (size_t i = 0; i < n; ++i) {
    const double d = glm::length(out[i] - pose.positions[i]);
    if (d > far) ++farCount;
    glm::vec3 sp;
    const int k = closestSegmentSurface(segs, pose.positions[i], sp);
    if (k < 0) continue;
    SegmentFitError& e = r.perSegment[size_t(k)];
    ++e.vertices;
    e.meanDistance += d;
    e.maxDistance = std::max(e.maxDistance, d);
    if (d > far) ++segFar[size_t(k)];
  }
  r.farShare = n ? double(farCount) / double(n) : 0.0;
  for (size_t k = 0; k < segs.size(); ++k) {
    SegmentFitError& e = r.perSegment[k];
    e.node = s.segments[k].node;
    e.bone = e.node >= 0 && e.node < int(c.nodes.size()) ? c.nodes[size_t(e.node)].name : std::string("(none)");
    e.radius = segs[k].radius;
    if (e.vertices) {
      e.meanDistance /= double(e.vertices);
      e.farShare = double(segFar[k]) / double(e.vertices);
    }
  }

  // Topology: the stand-in's pieces against the mesh's.
  std::vector<uint32_t> indices;
  for (size_t k = 0; k < pose.meshNodes.size(); ++k) {
    const Mesh& mesh = c.meshes[size_t(c.nodes[size_t(pose.meshNodes[k])].mesh)];
    for (uint32_t i : mesh.indices) indices.push_back(uint32_t(pose.firstVertex[k] + i));
  }
  r.meshComponents = weldedComponents(pose.positions, indices, float(1e-5 * diag));
  std::vector<int> segmentPiece;
  std::vector<size_t> pieceSize;
  if (settings.topologyResolution > 0 && !segs.empty())
    measureComponents(s, segs, settings.topologyResolution, r, segmentPiece, pieceSize);
  r.segmentPiece = segmentPiece;
  if (!pieceSize.empty())
    r.mainPiece = int(std::max_element(pieceSize.begin(), pieceSize.end()) - pieceSize.begin());

  // Verdict, naming bones.
  auto addBone = [&](const std::string& b) {
    if (std::find(r.poorBones.begin(), r.poorBones.end(), b) == r.poorBones.end()) r.poorBones.push_back(b);
  };
  if (r.standinComponents > std::max(1, r.meshComponents)) {
    const size_t main = size_t(std::max_element(pieceSize.begin(), pieceSize.end()) - pieceSize.begin());
    std::string bones;
    for (size_t k = 0; k < segs.size(); ++k)
      if (segmentPiece[k] >= 0 && size_t(segmentPiece[k]) != main) {
        addBone(r.perSegment[k].bone);
        if (bones.find("'" + r.perSegment[k].bone + "'") == std::string::npos)
          bones += (bones.empty() ? "'" : ", '") + r.perSegment[k].bone + "'";
      }
    r.problems.push_back(fmt("the stand-in is in %.0f pieces (the mesh in %.0f), largest gap %.3g (%.2f %% of the "
                             "diagonal); detached: ",
                             r.standinComponents, r.meshComponents, r.largestGap, 100.0 * r.largestGap / diag) +
                         bones);
  }
  if (r.farShare > settings.poorFarShare || r.meanError > settings.poorMeanFraction) {
    std::vector<size_t> order;
    for (size_t k = 0; k < segs.size(); ++k)
      if (r.perSegment[k].vertices && r.perSegment[k].farShare > settings.poorFarShare) order.push_back(k);
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return r.perSegment[a].farShare > r.perSegment[b].farShare; });
    std::string bones;
    for (size_t q = 0; q < order.size() && q < 8; ++q) {
      const auto& e = r.perSegment[order[q]];
      addBone(e.bone);
      bones += (q ? ", '" : "'") + e.bone + "'" + fmt(" (%.0f %% far)", 100.0 * e.farShare);
    }
    r.problems.push_back(fmt("%.1f %% of the vertices are farther than %.0f %% of the diagonal from the stand-in "
                             "(mean %.3g = %.2f %%)",
                             100.0 * r.farShare, 100.0 * settings.farFraction, r.meanDistance, 100.0 * r.meanError) +
                         (bones.empty() ? std::string() : "; worst bones: " + bones));
  }
  r.poor = !r.problems.empty();
  r.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string fitSummary(const FitReport& r) {
  const double diag = std::max(1e-12, r.diagonal);
  std::string s = fmt("mean %.3g (%.2f %%), max %.3g (%.2f %%) of a %.3g diagonal (scene units); ", r.meanDistance,
                      100.0 * r.meanDistance / diag, r.maxDistance, 100.0 * r.maxDistance / diag, r.diagonal) +
                  fmt("%.1f %% of vertices farther than %.0f %%", 100.0 * r.farShare, 100.0 * r.farFraction);
  if (r.standinComponents >= 0)
    s += fmt("; stand-in in %.0f piece(s), mesh in %.0f", r.standinComponents, r.meshComponents);
  return s;
}

FitFigures fitFigures(const FitReport& r) {
  FitFigures f;
  f.segments = r.segments;
  f.meanDistance = r.meanDistance;
  f.maxDistance = r.maxDistance;
  f.farShare = r.farShare;
  f.standinComponents = r.standinComponents;
  f.meshComponents = r.meshComponents;
  f.largestGap = r.largestGap;
  f.poor = r.poor;
  return f;
}

std::string repairSummary(const FitReport& r) {
  if (r.repairs.empty()) return {};
  const double diag = std::max(1e-12, r.diagonal);
  const FitFigures& b = r.beforeRepair;
  std::string what;
  for (const auto& a : r.repairs) what += (what.empty() ? "" : "; ") + a;
  std::string s = "repaired (" + what + "): ";
  if (b.standinComponents >= 0 && r.standinComponents >= 0)
    s += fmt("stand-in %.0f -> %.0f piece(s) (mesh %.0f), largest gap %.3g (%.2f %%) -> ", b.standinComponents,
             r.standinComponents, r.meshComponents, b.largestGap, 100.0 * b.largestGap / diag) +
         fmt("%.3g (%.2f %%); ", r.largestGap, 100.0 * r.largestGap / diag);
  s += fmt("far %.1f %% -> %.1f %%; ", 100.0 * b.farShare, 100.0 * r.farShare) +
       fmt("mean %.3g (%.2f %%) -> %.3g (%.2f %%); ", b.meanDistance, 100.0 * b.meanDistance / diag, r.meanDistance,
           100.0 * r.meanDistance / diag) +
       fmt("max %.3g (%.2f %%) -> %.3g (%.2f %%); ", b.maxDistance, 100.0 * b.maxDistance / diag, r.maxDistance,
           100.0 * r.maxDistance / diag) +
       fmt("%.0f -> %.0f segments", double(b.segments), double(r.segments));
  return s;
}

}  // namespace animorph
