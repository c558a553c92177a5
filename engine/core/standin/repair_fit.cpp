#include "core/standin/repair_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>

#include "core/field/skeleton.h"

namespace animorph {

namespace {

float percentileOf(std::vector<float> v, float p) {
  if (v.empty()) return 0.0f;
  const size_t k = std::min(v.size() - 1, size_t(std::clamp(p, 0.0f, 1.0f) * float(v.size() - 1) + 0.5f));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

// Signed distance of x to the capsule surface of one posed segment (< 0 inside).
float capsuleDistance(const glm::vec3& x, const glm::vec3& a, const glm::vec3& b, float r) {
  return glm::length(x - closestOnSegment(x, a, b)) - r;
}

// Unit principal axes of points (largest spread first) and their centroid: power iteration with deflation.
void principalAxes(const std::vector<glm::vec3>& pts, glm::vec3& centroid, glm::vec3 axes[3]) {
  centroid = glm::vec3(0.0f);
  for (const auto& p : pts) centroid += p;
  centroid /= float(std::max<size_t>(1, pts.size()));
  glm::mat3 cov(0.0f);
  for (const auto& p : pts) cov += glm::outerProduct(p - centroid, p - centroid);
  auto power = [](const glm::mat3& m, glm::vec3 v) {
    for (int i = 0; i < 64; ++i) {
      const glm::vec3 w = m * v;
      const float l = glm::length(w);
      if (l < 1e-30f) break;
      v = w / l;
    }
    return v;
  };
  axes[0] = glm::normalize(power(cov, glm::vec3(0.577f, 0.577f, 0.577f)));
  const float l0 = glm::dot(axes[0], cov * axes[0]);
  const glm::mat3 deflated = cov - l0 * glm::outerProduct(axes[0], axes[0]);
  glm::vec3 seed = std::abs(axes[0].x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  seed = glm::normalize(seed - axes[0] * glm::dot(seed, axes[0]));
  glm::vec3 e1 = power(deflated, seed);
  e1 = e1 - axes[0] * glm::dot(e1, axes[0]);
  axes[1] = glm::length(e1) > 1e-12f ? glm::normalize(e1) : seed;
  axes[2] = glm::normalize(glm::cross(axes[0], axes[1]));
}

struct Part {
  glm::vec3 a, b;
  float radius;
};

// n segments along u side by side across e (offsets spread over the vertices' extent along e),
// each fitted to the vertices nearest its line: ends at the 2nd and 98th percentiles along u
// pulled in by half a radius, radius the given percentile of their distances.
std::vector<Part> partsAlong(const std::vector<glm::vec3>& pts, const glm::vec3& centre, const glm::vec3& u,
                             const glm::vec3& e, int n, float radiusPercentile, float minRadius) {
  std::vector<float> across;
  for (const auto& p : pts) across.push_back(glm::dot(p - centre, e));
  const float lo = percentileOf(across, 0.05f), hi = percentileOf(across, 0.95f);
  const float mid = 0.5f * (lo + hi), half = 0.5f * (hi - lo) * (1.0f - 1.0f / float(n));
  std::vector<std::vector<glm::vec3>> sets(static_cast<size_t>(n));
  std::vector<glm::vec3> origin(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
    origin[size_t(k)] = centre + e * (n > 1 ? mid - half + 2.0f * half * float(k) / float(n - 1) : mid);
  for (const auto& p : pts) {
    size_t best = 0;
    float bd = INFINITY;
    for (size_t k = 0; k < origin.size(); ++k) {
      const glm::vec3 d = p - origin[k];
      const float dist = glm::length(d - u * glm::dot(d, u));
      if (dist < bd) { bd = dist; best = k; }
    }
    sets[best].push_back(p);
  }
  std::vector<Part> out;
  for (size_t k = 0; k < sets.size(); ++k) {
    if (sets[k].size() < 4) continue;
    std::vector<float> t, d;
    for (const auto& p : sets[k]) t.push_back(glm::dot(p - origin[k], u));
    float t0 = percentileOf(t, 0.02f), t1 = percentileOf(t, 0.98f);
    Part part{origin[k] + u * t0, origin[k] + u * t1, 0.0f};
    for (const auto& p : sets[k]) d.push_back(glm::length(p - closestOnSegment(p, part.a, part.b)));
    part.radius = std::max(minRadius, percentileOf(d, radiusPercentile));
    const float pull = std::min(0.5f * part.radius, 0.25f * (t1 - t0));
    t0 += pull;
    t1 -= pull;
    part.a = origin[k] + u * t0;
    part.b = origin[k] + u * t1;
    out.push_back(part);
  }
  return out;
}

// Mean |distance to the surface| of pts against the union of `others` (per point) and parts.
double unionError(const std::vector<glm::vec3>& pts, const std::vector<float>& others, const std::vector<Part>& parts) {
  double sum = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    float d = others[i];
    for (const Part& q : parts) d = std::min(d, capsuleDistance(pts[i], q.a, q.b, q.radius));
    sum += std::abs(d);
  }
  return pts.empty() ? 0.0 : sum / double(pts.size());
}

// Closest points of segments [a0, a1] and [b0, b1] (clamped parameters).
void closestBetweenSegments(const glm::vec3& a0, const glm::vec3& a1, const glm::vec3& b0, const glm::vec3& b1,
                            glm::vec3& p, glm::vec3& q) {
  const glm::vec3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const float aa = glm::dot(d1, d1), ee = glm::dot(d2, d2), f = glm::dot(d2, r);
  float s = 0.0f, t = 0.0f;
  if (aa < 1e-20f && ee < 1e-20f) {
    p = a0;
    q = b0;
    return;
  }
  if (aa < 1e-20f) {
    t = std::clamp(f / ee, 0.0f, 1.0f);
  } else {
    const float c = glm::dot(d1, r);
    if (ee < 1e-20f) {
      s = std::clamp(-c / aa, 0.0f, 1.0f);
    } else {
      const float b = glm::dot(d1, d2), den = aa * ee - b * b;
      s = den > 1e-20f ? std::clamp((b * f - c * ee) / den, 0.0f, 1.0f) : 0.0f;
      t = (b * s + f) / ee;
      if (t < 0.0f) {
        t = 0.0f;
        s = std::clamp(-c / aa, 0.0f, 1.0f);
      } else if (t > 1.0f) {
        t = 1.0f;
        s = std::clamp((b - c) / aa, 0.0f, 1.0f);
      }
    }
  }
  p = a0 + d1 * s;
  q = b0 + d2 * t;
}

int excessPieces(const FitReport& r) {
  return r.standinComponents < 0 ? 0 : std::max(0, r.standinComponents - std::max(1, r.meshComponents));
}

// Whether measurement m is better than r: fewer excess pieces first; then, with no more vertices
// the projection misses (failures stuck within float noise of the surface do not count: where they
// fall depends on the file's unit), fewer far vertices or a smaller mean.
bool better(const FitReport& m, const FitReport& r) {
  if (excessPieces(m) != excessPieces(r)) return excessPieces(m) < excessPieces(r);
  if (m.projectionMisses > r.projectionMisses) return false;
  if (m.farShare < r.farShare - 1e-3) return true;
  return m.farShare <= r.farShare + 1e-3 && m.meanDistance < 0.97 * r.meanDistance;
}

std::string boneName(const Character& c, int node) {
  return node >= 0 && node < int(c.nodes.size()) ? c.nodes[size_t(node)].name : std::string("(none)");
}

struct RepairState {
  const Character& c;
  const CharacterPose& pose;
  const std::vector<int>& vertexNode;
  const ProjectionSettings& projection;
  const FitQualitySettings& quality;
  float radiusPercentile;
  const FitRepairSettings& settings;
  float minRadius;
  std::vector<char> bridge;  // per segment of the current stand-in: added by a bridge repair
};

StandinSegment toNodeSpace(const CharacterPose& pose, int node, const Part& p) {
  const glm::mat4& g = pose.globals[size_t(node)];
  const glm::mat4 inv = glm::inverse(g);
  StandinSegment seg;
  seg.node = node;
  seg.a = glm::vec3(inv * glm::vec4(p.a, 1.0f));
  seg.b = glm::vec3(inv * glm::vec4(p.b, 1.0f));
  seg.radius = p.radius / std::max(1e-12f, radiusScale(g));
  return seg;
}

struct PartSearch {
  std::vector<Part> parts;
  double error = INFINITY;
};

// The best segments for pts (mean |distance| with the surfaces of `others` counted): along their
// principal axis or the bone's axis, one segment or up to maxParts side by side across the widest
// direction; a part more must cut the error by 3 %.
PartSearch bestParts(const RepairState& st, const std::vector<glm::vec3>& pts, const std::vector<float>& others,
                     const glm::vec3& boneAxis, int maxParts) {
  PartSearch best;
  glm::vec3 centre, axes[3];
  principalAxes(pts, centre, axes);
  std::vector<glm::vec3> directions{axes[0]};
  if (glm::length(boneAxis) > 0.0f) directions.push_back(glm::normalize(boneAxis));
  for (const glm::vec3& u : directions) {
    // The widest direction across u, from the vertices' spread perpendicular to it.
    std::vector<glm::vec3> perp;
    for (const auto& p : pts) perp.push_back(p - centre - u * glm::dot(p - centre, u));
    glm::vec3 pc, pa[3];
    principalAxes(perp, pc, pa);
    glm::vec3 e = pa[0] - u * glm::dot(pa[0], u);
    if (glm::length(e) < 1e-6f) e = axes[1];
    e = glm::normalize(e);
    for (int n = 1; n <= maxParts; ++n) {
      std::vector<Part> parts = partsAlong(pts, centre, u, e, n, st.radiusPercentile, st.minRadius);
      if (parts.empty()) continue;
      const double err = unionError(pts, others, parts);
      if (err < best.error * 0.97) best = {std::move(parts), err};
    }
  }
  return best;
}

// Re-places node's own segments on the vertices bound to it when that fits them much better:
// along their principal axis or the bone's current axis, one segment or several side by side;
// or, where the node owns small bones merged into it (a tail whose first joint sits in the
// body), each of those gets a segment on its own vertices again, bound to it. Returns the
// action line, empty when the current segments stay.
std::string replaceNode(RepairState& st, Standin& s, int node, bool unmerge) {
  std::vector<glm::vec3> pts;
  std::vector<int> bone;  // each vertex's dominant bone
  for (size_t i = 0; i < st.vertexNode.size(); ++i)
    if (st.vertexNode[i] == node) {
      pts.push_back(st.pose.positions[i]);
      bone.push_back(st.pose.dominantNode[i]);
    }
  if (pts.size() < 16) return {};
  const auto posed = poseStandin(s, st.pose.globals, glm::mat4(1.0f));
  std::vector<Part> mine;
  std::vector<float> others(pts.size(), INFINITY);
  glm::vec3 boneAxis(0.0f);
  for (size_t k = 0; k < posed.size(); ++k) {
    const PosedSegment& q = posed[k];
    if (s.segments[k].node == node && !st.bridge[k]) {
      mine.push_back({q.a, q.b, q.radius});
      if (glm::length(q.b - q.a) > glm::length(boneAxis)) boneAxis = q.b - q.a;
      continue;
    }
    for (size_t i = 0; i < pts.size(); ++i) others[i] = std::min(others[i], capsuleDistance(pts[i], q.a, q.b, q.radius));
  }
  if (mine.empty()) return {};
  const size_t room = st.settings.maxSegments - std::min(st.settings.maxSegments, s.segments.size() - mine.size());
  const double before = unionError(pts, others, mine);
  // Candidate 1: every vertex of the node together.
  std::vector<std::pair<int, Part>> best;
  PartSearch all = bestParts(st, pts, others, boneAxis, std::min(st.settings.maxSideBySide, int(room)));
  double bestError = all.error;
  for (const Part& p : all.parts) best.push_back({node, p});
  // Candidate 2: the node's own vertices, and each merged bone's own (a segment each).
  std::vector<int> merged;
  for (int b : bone)
    if (b != node && std::find(merged.begin(), merged.end(), b) == merged.end()) merged.push_back(b);
  if (unmerge && !merged.empty() && merged.size() + 1 <= room) {
    std::vector<std::pair<int, Part>> split;
    std::vector<glm::vec3> own;
    for (size_t i = 0; i < pts.size(); ++i)
      if (bone[i] == node) own.push_back(pts[i]);
    const int maxOwn = std::min(st.settings.maxSideBySide, int(room - merged.size()));
    if (own.size() >= 16)
      for (const Part& p : bestParts(st, own, std::vector<float>(own.size(), INFINITY), boneAxis, maxOwn).parts)
        split.push_back({node, p});
    for (int b : merged) {
      std::vector<glm::vec3> theirs;
      for (size_t i = 0; i < pts.size(); ++i)
        if (bone[i] == b) theirs.push_back(pts[i]);
      if (theirs.size() < 8) continue;
      for (const Part& p : bestParts(st, theirs, std::vector<float>(theirs.size(), INFINITY), glm::vec3(0.0f), 1).parts)
        split.push_back({b, p});
    }
    std::vector<Part> parts;
    for (const auto& [n, p] : split) parts.push_back(p);
    const double err = parts.empty() ? INFINITY : unionError(pts, others, parts);
    if (err < bestError) {
      bestError = err;
      best = std::move(split);
    }
  }
  if (best.empty() || bestError > double(st.settings.replaceGain) * before) return {};
  std::vector<StandinSegment> kept;
  std::vector<char> keptBridge;
  for (size_t k = 0; k < s.segments.size(); ++k)
    if (s.segments[k].node != node || st.bridge[k]) {
      kept.push_back(s.segments[k]);
      keptBridge.push_back(st.bridge[k]);
    }
  std::string bones;
  for (const auto& [n, p] : best) {
    kept.push_back(toNodeSpace(st.pose, n, p));
    keptBridge.push_back(0);
    if (n != node && bones.find("'" + boneName(st.c, n) + "'") == std::string::npos)
      bones += (bones.empty() ? "'" : ", '") + boneName(st.c, n) + "'";
  }
  s.segments = std::move(kept);
  st.bridge = std::move(keptBridge);
  const size_t onNode = size_t(std::count_if(best.begin(), best.end(), [&](const auto& q) { return q.first == node; }));
  return "re-placed '" + boneName(st.c, node) + "' on its " + std::to_string(pts.size()) + " vertices: " +
         std::to_string(onNode) + (onNode > 1 ? " segments side by side" : " segment") +
         (bones.empty() ? std::string() : ", and a segment each on the vertices of " + bones) +
         fmt(" (their mean distance %.3g -> %.3g)", before, bestError);
}

bool isAncestor(const Character& c, int ancestor, int node) {
  for (int p = node; p >= 0; p = c.nodes[size_t(p)].parent)
    if (p == ancestor) return true;
  return false;
}

struct Link {
  size_t i = 0, j = 0;  // segments in two different pieces
  glm::vec3 p, q;       // closest points on them
  float cost = INFINITY;
};

// Two parallel segments of one bone side by side (a thin sheet split across its width) merge into
// one surface when both radii reach past half the distance of their axes. Returns false when the
// segments are not parallel (then a bridge joins them).
bool widenSideBySide(RepairState& st, Standin& s, const std::vector<PosedSegment>& posed, const Link& l) {
  const glm::vec3 di = posed[l.i].b - posed[l.i].a, dj = posed[l.j].b - posed[l.j].a;
  if (glm::length(di) < 1e-12f || glm::length(dj) < 1e-12f) return false;
  if (std::abs(glm::dot(glm::normalize(di), glm::normalize(dj))) < 0.9f) return false;
  const float reach = 0.6f * glm::length(l.q - l.p);
  const float scale = std::max(1e-12f, radiusScale(st.pose.globals[size_t(s.segments[l.i].node)]));
  for (size_t k : {l.i, l.j}) s.segments[k].radius = std::max(s.segments[k].radius, std::max(reach, st.minRadius) / scale);
  return true;
}

// Bridges the stand-in's detached pieces to the rest: the cheapest links between pieces (a spanning
// tree over the pieces, preferring segments of related bones along the chain) until the stand-in has
// no more pieces than the mesh. Returns the action lines.
std::vector<std::string> bridgePieces(RepairState& st, Standin& s, const FitReport& r) {
  std::vector<std::string> actions;
  const int pieces = r.standinComponents;
  if (excessPieces(r) == 0 || r.segmentPiece.size() != s.segments.size() || pieces < 2) return actions;
  const auto posed = poseStandin(s, st.pose.globals, glm::mat4(1.0f));
  // The cheapest link between every pair of pieces.
  std::vector<Link> best(size_t(pieces * pieces));
  for (size_t i = 0; i < posed.size(); ++i)
    for (size_t j = 0; j < posed.size(); ++j) {
      const int pi = r.segmentPiece[i], pj = r.segmentPiece[j];
      if (pi < 0 || pj < 0 || pi >= pj) continue;
      Link l;
      l.i = i;
      l.j = j;
      closestBetweenSegments(posed[i].a, posed[i].b, posed[j].a, posed[j].b, l.p, l.q);
      const int ni = s.segments[i].node, nj = s.segments[j].node;
      const bool related = ni == nj || isAncestor(st.c, ni, nj) || isAncestor(st.c, nj, ni);
      // Along the bone chain first (side-by-side parts of one bone before that): an unrelated
      // bone is three times as far.
      l.cost = glm::length(l.q - l.p) * (ni == nj ? 0.9f : related ? 1.0f : 3.0f);
      Link& b = best[size_t(pi * pieces + pj)];
      if (l.cost < b.cost) b = l;
    }
  std::vector<Link> links;
  for (const Link& l : best)
    if (std::isfinite(l.cost)) links.push_back(l);
  std::sort(links.begin(), links.end(), [](const Link& a, const Link& b) { return a.cost < b.cost; });
  std::vector<int> group(static_cast<size_t>(pieces));
  std::iota(group.begin(), group.end(), 0);
  auto find = [&](int x) {
    while (group[size_t(x)] != x) x = group[size_t(x)] = group[size_t(group[size_t(x)])];
    return x;
  };
  int toJoin = excessPieces(r);
  for (const Link& l : links) {
    if (toJoin == 0 || s.segments.size() >= st.settings.maxSegments) break;
    const int gi = find(r.segmentPiece[l.i]), gj = find(r.segmentPiece[l.j]);
    if (gi == gj) continue;
    group[size_t(gi)] = gj;
    --toJoin;
    const PosedSegment &si = posed[l.i], &sj = posed[l.j];
    const int ni = s.segments[l.i].node, nj = s.segments[l.j].node;
    if (ni == nj && widenSideBySide(st, s, posed, l)) {
      actions.push_back("merged two side-by-side segments of '" + boneName(st.c, ni) + "'" +
                        fmt(" across a gap of %.3g (radius %.3g)", glm::length(l.q - l.p), s.segments[l.i].radius *
                                                                        radiusScale(st.pose.globals[size_t(ni)])));
      continue;
    }
    const float lo = std::max(st.minRadius, 0.5f * std::min(si.radius, sj.radius)), hi = std::max(si.radius, sj.radius);
    // As thick as the mesh around the bridge's middle, within the two segments' radii.
    std::vector<float> d;
    const glm::vec3 axis = l.q - l.p;
    const float len2 = glm::dot(axis, axis);
    for (const auto& x : st.pose.positions) {
      const float t = len2 > 0.0f ? glm::dot(x - l.p, axis) / len2 : 0.5f;
      if (t < 0.15f || t > 0.85f) continue;
      const float dist = glm::length(x - (l.p + axis * t));
      if (dist < 2.0f * hi) d.push_back(dist);
    }
    const float radius = std::clamp(d.empty() ? lo : percentileOf(d, st.radiusPercentile), lo, hi);
    // Bound to the deeper bone of the two, so the bridge turns with the joint between them.
    const int node = isAncestor(st.c, ni, nj) ? nj : ni;
    s.segments.push_back(toNodeSpace(st.pose, node, Part{l.p, l.q, radius}));
    st.bridge.push_back(1);
    actions.push_back("bridged '" + boneName(st.c, ni) + "' to '" + boneName(st.c, nj) + "'" +
                      fmt(" across a gap of %.3g (radius %.3g)", glm::length(axis), radius));
  }
  return actions;
}


// Re-places node's segments (with its merged bones given back their own segments, else without),
// bridging any piece that falls apart; kept when the measurement says it is better than r.
bool tryReplace(RepairState& st, Standin& s, FitReport& r, int node, std::vector<std::string>& repairs) {
  for (bool unmerge : {true, false}) {
    Standin trial = s;
    const std::vector<char> savedBridge = st.bridge;
    const std::string action = replaceNode(st, trial, node, unmerge);
    if (action.empty()) continue;
    FitReport m = measureFitQuality(st.c, trial, st.pose, st.projection, st.quality);
    std::vector<std::string> done{action};
    if (excessPieces(m) > excessPieces(r)) {
      // The re-placed segments left a piece apart (a tail's): bridge it before judging.
      const auto bridges = bridgePieces(st, trial, m);
      if (!bridges.empty()) {
        m = measureFitQuality(st.c, trial, st.pose, st.projection, st.quality);
        done.insert(done.end(), bridges.begin(), bridges.end());
      }
    }
    if (better(m, r)) {
      s = std::move(trial);
      r = std::move(m);
      repairs.insert(repairs.end(), done.begin(), done.end());
      return true;
    }
    st.bridge = savedBridge;
  }
  return false;
}

// Bridges r's detached pieces; kept when the measurement says it is better.
bool tryBridge(RepairState& st, Standin& s, FitReport& r, std::vector<std::string>& repairs) {
  if (excessPieces(r) == 0) return false;
  Standin trial = s;
  const std::vector<char> saved = st.bridge;
  const auto actions = bridgePieces(st, trial, r);
  if (actions.empty()) return false;
  FitReport m = measureFitQuality(st.c, trial, st.pose, st.projection, st.quality);
  if (!better(m, r)) {
    st.bridge = saved;
    return false;
  }
  s = std::move(trial);
  r = std::move(m);
  repairs.insert(repairs.end(), actions.begin(), actions.end());
  return true;
}

}  // namespace

FitReport repairStandinFit(const Character& c, const CharacterPose& pose, const std::vector<int>& vertexNode,
                           Standin& s, const FitReport& first, const ProjectionSettings& projection,
                           const FitQualitySettings& quality, float radiusPercentile,
                           const FitRepairSettings& settings) {
  if (!settings.enabled || !first.poor || vertexNode.size() != pose.positions.size()) return first;
  RepairState st{c, pose, vertexNode, projection, quality, radiusPercentile, settings,
                 float(1e-3 * std::max(1e-12, first.diagonal)), std::vector<char>(s.segments.size(), 0)};
  // A bridge thinner than about a cell of the components check would not count as one.
  if (quality.topologyResolution > 0)
    st.minRadius = std::max(st.minRadius, float(0.6 * first.diagonal / quality.topologyResolution));
  const Standin original = s;
  FitReport r = first;
  std::vector<std::string> repairs;
  for (int round = 0; round < settings.maxRounds && r.poor; ++round) {
    bool progress = false;
    // Bones with many far vertices, worst first: re-place their segments one bone at a time.
    std::vector<std::pair<double, int>> worst;
    for (size_t k = 0; k < r.perSegment.size() && k < s.segments.size(); ++k) {
      const SegmentFitError& e = r.perSegment[k];
      if (!st.bridge[k] && e.vertices > 0 && e.farShare > quality.poorFarShare)
        worst.push_back({-e.farShare * double(e.vertices), s.segments[k].node});
    }
    std::sort(worst.begin(), worst.end());
    std::vector<int> tried;
    for (const auto& [score, node] : worst) {
      if (std::find(tried.begin(), tried.end(), node) != tried.end()) continue;
      tried.push_back(node);
      progress = tryReplace(st, s, r, node, repairs) || progress;
    }
    // Pieces: bridge them along the bone chain.
    progress = tryBridge(st, s, r, repairs) || progress;
    if (!progress) break;
  }
  if (repairs.empty()) return first;
  if (r.poor) {
    // Not repairable: the first fit stays, as it was measured; the note says what was tried.
    s = original;
    FitReport out = first;
    std::string tried;
    for (const auto& a : repairs) tried += (tried.empty() ? "" : "; ") + a;
    out.notes.push_back("automatic repair tried (" + tried + ") but the fit stays poor; the first fit is kept");
    return out;
  }
  r.repairs = std::move(repairs);
  r.beforeRepair = fitFigures(first);
  return r;
}

}  // namespace animorph
