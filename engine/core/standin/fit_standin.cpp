#include "core/standin/fit_standin.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/field/skeleton.h"
#include "core/standin/character_pose.h"

namespace animorph {

namespace {

float percentile(std::vector<float>& v, float p) {
  if (v.empty()) return 0.0f;
  const size_t k = std::min(v.size() - 1, size_t(std::clamp(p, 0.0f, 1.0f) * float(v.size() - 1) + 0.5f));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

// Principal axis of points (power iteration on the covariance), and the centroid.
glm::vec3 principalAxis(const std::vector<glm::vec3>& pts, glm::vec3& centroid) {
  centroid = glm::vec3(0.0f);
  for (const auto& p : pts) centroid += p;
  centroid /= float(std::max<size_t>(1, pts.size()));
  glm::mat3 cov(0.0f);
  for (const auto& p : pts) {
    const glm::vec3 d = p - centroid;
    cov += glm::outerProduct(d, d);
  }
  glm::vec3 v(0.577f, 0.577f, 0.577f);
  for (int i = 0; i < 64; ++i) {
    glm::vec3 w = cov * v;
    const float l = glm::length(w);
    if (l < 1e-20f) return glm::vec3(1, 0, 0);
    v = w / l;
  }
  return v;
}

struct Candidate {
  Candidate(int n, const glm::vec3& a0, const glm::vec3& b0) : node(n), a(a0), b(b0) {}
  int node;
  glm::vec3 a, b;
  bool shrinkA = false, shrinkB = false;  // ends free to pull in by half a radius
  std::vector<float> dist;
  std::vector<glm::vec3> pts;
  float radius = 0.0f;
};

// Each vertex belongs to its closest segment (its distance and itself added to it).
void assignToClosestSegment(const std::vector<glm::vec3>& pts, std::vector<Candidate>& mine) {
  for (const auto& p : pts) {
    size_t best = 0;
    float bd = INFINITY;
    for (size_t k = 0; k < mine.size(); ++k) {
      const float d = glm::length(p - closestOnSegment(p, mine[k].a, mine[k].b));
      if (d < bd) { bd = d; best = k; }
    }
    mine[best].dist.push_back(bd);
    mine[best].pts.push_back(p);
  }
}

// A bone whose vertices spread much wider one way than the other across it (a
// plate, a fin, a disc) gets several parallel segments spanning the wide
// direction instead of one round tube: one tube cannot fit a flat shape.
void splitFlat(Candidate& cd, float minLen, std::vector<Candidate>& out) {
  const glm::vec3 ab = cd.b - cd.a;
  const float len = glm::length(ab);
  if (len < minLen || cd.pts.size() < 16) {
    out.push_back(std::move(cd));
    return;
  }
  const glm::vec3 axis = ab / len;
  // Principal direction of the vertices' offsets across the segment.
  std::vector<glm::vec3> perp;
  perp.reserve(cd.pts.size());
  for (const auto& p : cd.pts) {
    const glm::vec3 d = p - cd.a;
    perp.push_back(d - axis * glm::dot(d, axis));
  }
  glm::vec3 centroid;
  glm::vec3 e = principalAxis(perp, centroid);
  e = glm::normalize(e - axis * glm::dot(e, axis));
  const glm::vec3 f = glm::normalize(glm::cross(axis, e));
  std::vector<float> ue, uf;
  for (const auto& d : perp) {
    ue.push_back(std::abs(glm::dot(d - centroid, e)));
    uf.push_back(std::abs(glm::dot(d - centroid, f)));
  }
  const float wide = percentile(ue, 0.9f), thin = std::max(percentile(uf, 0.9f), 1e-6f);
  // Spacing about 1.3 thicknesses: neighbours blend into one smooth sheet.
  const int n = std::min(8, int(std::lround(1.5f * wide / thin)));
  if (wide < 2.5f * thin || n < 2) {
    out.push_back(std::move(cd));
    return;
  }
  // n parallel segments spread over the wide extent, each as thick as the shape.
  const float half = wide - thin;
  std::vector<Candidate> parts;
  for (int k = 0; k < n; ++k) {
    const float o = -half + 2.0f * half * float(k) / float(n - 1);
    Candidate c(cd.node, cd.a + centroid + e * o, cd.b + centroid + e * o);
    c.shrinkA = cd.shrinkA;
    c.shrinkB = cd.shrinkB;
    parts.push_back(std::move(c));
  }
  assignToClosestSegment(cd.pts, parts);
  for (auto& c : parts)
    if (!c.dist.empty()) out.push_back(std::move(c));
}

const AnimationClip* pickClip(const Character& c, int clip) {
  return clip >= 0 && clip < static_cast<int>(c.clips.size()) ? &c.clips[size_t(clip)] : nullptr;
}

// What the steps of one fit share: the character in its fitting pose, the rig, and which joints
// carry segments.
struct FitContext {
  const Character& c;
  const FitSettings& settings;
  const CharacterPose& pose;
  float diag = 0.0f;    // the posed mesh's bounding-box diagonal
  float minLen = 0.0f;  // segments shorter than this are points
  std::vector<char> rig{};                          // rigNodes(c)
  std::vector<std::vector<glm::vec3>> dominated{};  // each node's vertices (its dominant ones)
  std::vector<char> active{};                       // joints that carry segments
  glm::vec3 jointPos(int n) const { return glm::vec3(pose.globals[size_t(n)][3]); }
  int rigParent(int n) const {
    int p = c.nodes[size_t(n)].parent;
    while (p >= 0 && !rig[size_t(p)]) p = c.nodes[size_t(p)].parent;
    return p;
  }
};

// Joints that carry segments: rig joints with vertices of their own. Counts the others.
void markActiveJoints(FitContext& x, FitReport& report) {
  x.active.assign(x.c.nodes.size(), 0);
  for (size_t j = 0; j < x.c.nodes.size(); ++j) {
    x.active[j] = x.rig[j] && !x.dominated[j].empty();
    if (x.rig[j] && x.dominated[j].empty()) ++report.bonesOmitted;
  }
}

// True when node n or a node below it is active.
bool hasActiveBelow(const FitContext& x, int n) {
  std::vector<int> st{n};
  while (!st.empty()) {
    const int k = st.back();
    st.pop_back();
    if (x.active[size_t(k)]) return true;
    for (int ch : x.c.nodes[size_t(k)].children) st.push_back(ch);
  }
  return false;
}

// Where a bone's segments go: its child joints, or (bridging) its nearest
// active descendants through joints without vertices. `ends` are inactive
// rig children with no active descendant (end bones): a leaf direction only.
void targetsOf(const FitContext& x, int j, std::vector<int>& to, std::vector<int>& ends) {
  const Character& c = x.c;
  to.clear();
  ends.clear();
  std::vector<int> stack(c.nodes[size_t(j)].children.rbegin(), c.nodes[size_t(j)].children.rend());
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (!x.settings.bridgeHelpers) {
      if (x.rig[size_t(n)]) to.push_back(n);
      continue;
    }
    if (x.active[size_t(n)]) {
      to.push_back(n);
      continue;
    }
    for (auto it = c.nodes[size_t(n)].children.rbegin(); it != c.nodes[size_t(n)].children.rend(); ++it)
      stack.push_back(*it);
    if (x.rig[size_t(n)] && c.nodes[size_t(n)].parent == j) ends.push_back(n);
  }
  // End bones only count where no active joint lies below them.
  ends.erase(std::remove_if(ends.begin(), ends.end(), [&](int n) { return hasActiveBelow(x, n); }), ends.end());
}

// The number of vertices each node's sub-tree dominates.
std::vector<size_t> subtreeVertexCounts(const FitContext& x) {
  const Character& c = x.c;
  std::vector<size_t> subtreeVerts(c.nodes.size(), 0);
  for (size_t j = c.nodes.size(); j-- > 0;) {
    // Children have larger indices in most files, but do not rely on it.
    std::vector<int> st{int(j)};
    size_t sum = 0;
    while (!st.empty()) {
      const int k = st.back();
      st.pop_back();
      sum += x.dominated[size_t(k)].size();
      for (int ch : c.nodes[size_t(k)].children) st.push_back(ch);
    }
    subtreeVerts[j] = sum;
  }
  return subtreeVerts;
}

// A joint is inside its owner's body when it lies within the median distance
// of the owner's vertices from the owner's joint, or within the box of those
// vertices shrunk by 2 % (a brow bone under the forehead).
struct JointBodies {
  std::vector<float> roughRadius;
  std::vector<Bounds> body;
};

JointBodies jointBodies(const FitContext& x) {
  JointBodies b;
  b.roughRadius.assign(x.c.nodes.size(), 0.0f);
  b.body.resize(x.c.nodes.size());
  for (size_t j = 0; j < x.c.nodes.size(); ++j) {
    if (!x.active[j]) continue;
    const glm::vec3 P = x.jointPos(int(j));
    std::vector<float> d;
    for (const auto& p : x.dominated[j]) {
      d.push_back(glm::length(p - P));
      b.body[j].add(p);
    }
    b.roughRadius[j] = percentile(d, 0.5f);
    const glm::vec3 inset = 0.02f * b.body[j].size();
    b.body[j].min += inset;
    b.body[j].max -= inset;
  }
  return b;
}

// Small bones whose joint lies inside the tube of the bone that owns them
// give their vertices to it (no blob of their own, no fan of segments).
// Returns each node's owner (itself when active and not merged; -1: inactive).
std::vector<int> mergeSmallBones(const FitContext& x, FitReport& report) {
  const Character& c = x.c;
  std::vector<int> owner(c.nodes.size(), -1);
  const std::vector<size_t> subtreeVerts = subtreeVertexCounts(x);
  const JointBodies b = jointBodies(x);
  auto inside = [&](int j, int o) {
    const glm::vec3 q = x.jointPos(j);
    return glm::length(q - x.jointPos(o)) < b.roughRadius[size_t(o)] ||
           (glm::all(glm::greaterThanEqual(q, b.body[size_t(o)].min)) &&
            glm::all(glm::lessThanEqual(q, b.body[size_t(o)].max)));
  };
  std::vector<int> order;  // parents before children
  for (int r : c.roots) order.push_back(r);
  for (size_t q = 0; q < order.size(); ++q)
    for (int ch : c.nodes[size_t(order[q])].children) order.push_back(ch);
  for (int j : order) {
    if (!x.active[size_t(j)]) continue;
    owner[size_t(j)] = j;
    if (!x.settings.mergeSmallBones) continue;
    int a = x.rigParent(j);
    while (a >= 0 && !x.active[size_t(a)]) a = x.rigParent(a);
    if (a < 0) continue;
    const int o = owner[size_t(a)];
    if (inside(j, o) && subtreeVerts[size_t(j)] * 4 < x.dominated[size_t(o)].size()) {
      owner[size_t(j)] = o;
      ++report.bonesMerged;
    }
  }
  return owner;
}

// No joint with vertices below: a segment towards the end bone along which the
// vertices reach farthest, as far as they reach. False when none reaches past minLen.
bool segmentTowardsEndBone(const FitContext& x, int j, const std::vector<glm::vec3>& pts,
                           const std::vector<int>& ends, std::vector<Candidate>& mine) {
  const glm::vec3 P = x.jointPos(j);
  float best = x.minLen;
  glm::vec3 bestDir(0.0f);
  for (int e : ends) {
    const glm::vec3 Q = x.jointPos(e);
    if (glm::length(Q - P) <= x.minLen) continue;
    const glm::vec3 dir = glm::normalize(Q - P);
    std::vector<float> u;
    for (const auto& p : pts) u.push_back(glm::dot(p - P, dir));
    const float far = percentile(u, 0.9f);
    if (far > best) { best = far; bestDir = dir; }
  }
  if (glm::length(bestDir) <= 0.0f) return false;
  Candidate cd{j, P, P + bestDir * best};
  cd.shrinkB = true;
  mine.push_back(cd);
  return true;
}

// Leaf (or every child at the joint itself): a segment along the parent bone's
// direction, else along the vertices' principal axis (noted in the report).
void leafSegment(const FitContext& x, int j, const std::vector<glm::vec3>& pts, std::vector<Candidate>& mine,
                 FitReport& report) {
  const glm::vec3 P = x.jointPos(j);
  const int par = x.rigParent(j);
  glm::vec3 dir(0.0f);
  if (par >= 0 && glm::length(P - x.jointPos(par)) > x.minLen) dir = glm::normalize(P - x.jointPos(par));
  std::vector<float> u;
  if (glm::length(dir) > 0.0f) {
    for (const auto& p : pts) u.push_back(glm::dot(p - P, dir));
    const float far = percentile(u, 0.9f);
    if (far > x.minLen) {
      Candidate cd{j, P, P + dir * far};
      cd.shrinkB = true;
      mine.push_back(cd);
      return;
    }
  }
  glm::vec3 centroid;
  const glm::vec3 axis = principalAxis(pts, centroid);
  u.clear();
  for (const auto& p : pts) u.push_back(glm::dot(p - centroid, axis));
  std::vector<float> u2 = u;
  float lo = percentile(u, 0.1f), hi = percentile(u2, 0.9f);
  if (hi - lo < x.minLen) { lo -= 0.5f * x.minLen; hi += 0.5f * x.minLen; }
  Candidate cd{j, centroid + axis * lo, centroid + axis * hi};
  cd.shrinkA = cd.shrinkB = true;
  mine.push_back(cd);
  report.notes.push_back("node '" + x.c.nodes[size_t(j)].name +
                         "': no child bone; segment along its vertices' principal axis");
}


// The segments of active joint j fitted to its vertices pts (its own and those of the bones merged
// into it), with their radii, appended to cands.
void fitJointSegments(const FitContext& x, int j, const std::vector<glm::vec3>& pts, std::vector<Candidate>& cands,
                      FitReport& report) {
  const glm::vec3 P = x.jointPos(j);
  std::vector<int> to, ends;
  targetsOf(x, j, to, ends);
  std::vector<Candidate> mine;
  for (int ch : to) {
    const glm::vec3 Q = x.jointPos(ch);
    if (glm::length(Q - P) > x.minLen) mine.emplace_back(j, P, Q);
    if (x.settings.bridgeHelpers && x.c.nodes[size_t(ch)].parent != j) ++report.helperBridges;
  }
  if (mine.empty() && !segmentTowardsEndBone(x, j, pts, ends, mine)) leafSegment(x, j, pts, mine, report);
  assignToClosestSegment(pts, mine);
  std::vector<Candidate> split;
  for (auto& cd : mine)
    if (!cd.dist.empty()) splitFlat(cd, x.minLen, split);
  for (auto& cd : split) {
    cd.radius = std::max(1e-3f * x.diag, percentile(cd.dist, x.settings.radiusPercentile));
    cd.pts.clear();
    cd.pts.shrink_to_fit();
    cands.push_back(std::move(cd));
  }
}

// The candidates as the stand-in's segments, in their nodes' spaces; free ends pull in by half a
// radius (the surface reaches past a segment's end); the sharpness follows the median radius.
void buildSegments(const FitContext& x, std::vector<Candidate>& cands, Standin& s) {
  std::vector<float> radii;
  for (const auto& cd : cands) radii.push_back(cd.radius);
  const float medianR = percentile(radii, 0.5f);
  s.kind = x.settings.kind;
  s.sharpness = x.settings.sharpnessTimesRadius / std::max(1e-6f, medianR);
  for (auto& cd : cands) {
    glm::vec3 d = cd.b - cd.a;
    const float len = glm::length(d);
    if (len > 0.0f) {
      d /= len;
      float room = len - x.minLen;
      float pull = std::min(0.5f * cd.radius, room * 0.5f);
      if (pull > 0.0f) {
        if (cd.shrinkA) cd.a += d * pull;
        if (cd.shrinkB) cd.b -= d * pull;
      }
    }
    const glm::mat4 inv = glm::inverse(x.pose.globals[size_t(cd.node)]);
    StandinSegment seg;
    seg.node = cd.node;
    seg.a = glm::vec3(inv * glm::vec4(cd.a, 1.0f));
    seg.b = glm::vec3(inv * glm::vec4(cd.b, 1.0f));
    // Radii are stored in the node's space too (poseStandin scales them back).
    seg.radius = cd.radius / std::max(1e-12f, radiusScale(x.pose.globals[size_t(cd.node)]));
    s.segments.push_back(seg);
  }
}

// Measures the fit and, where it is poor and repair is on, repairs it; the report keeps the fit's
// own counts and notes.
void measureAndRepair(const FitContext& x, const std::vector<int>& owner, FitResult& result) {
  const Character& c = x.c;
  const FitSettings& settings = x.settings;
  Standin& s = result.standin;
  FitReport m = measureFitQuality(c, s, x.pose, settings.projection, settings.quality);
  if (m.poor && settings.repair.enabled) {
    std::vector<int> vertexNode(x.pose.positions.size(), -1);
    for (size_t i = 0; i < vertexNode.size(); ++i) vertexNode[i] = owner[size_t(x.pose.dominantNode[i])];
    m = repairStandinFit(c, x.pose, vertexNode, s, m, settings.projection, settings.quality,
                         settings.radiusPercentile, settings.repair);
    result.report.segments = s.segments.size();
  }
  m.bonesOmitted = result.report.bonesOmitted;
  m.bonesMerged = result.report.bonesMerged;
  m.helperBridges = result.report.helperBridges;
  m.notes.insert(m.notes.begin(), result.report.notes.begin(), result.report.notes.end());
  result.report = std::move(m);
}

}  // namespace

FitReport measureStandinFit(const Character& c, const Standin& s, const FitSettings& settings) {
  const CharacterPose pose = poseCharacter(c, pickClip(c, settings.clip), settings.clipTimeSec, glm::mat4(1.0f));
  return measureFitQuality(c, s, pose, settings.projection, settings.quality);
}

Result<FitResult> fitStandin(const Character& c, const FitSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string name = c.sourcePath.empty() ? std::string("character") : c.sourcePath;
  if (settings.clip >= static_cast<int>(c.clips.size()))
    return Error{name + ": clip " + std::to_string(settings.clip) + " does not exist (" +
                 std::to_string(c.clips.size()) + " clips)"};
  const CharacterPose pose = poseCharacter(c, pickClip(c, settings.clip), settings.clipTimeSec, glm::mat4(1.0f));
  if (pose.positions.empty()) return Error{name + ": no mesh vertices to fit a stand-in to"};
  FitContext x{c, settings, pose};
  Bounds box;
  for (const auto& p : pose.positions) box.add(p);
  x.diag = std::max(1e-6f, box.diagonal());
  x.minLen = 1e-3f * x.diag;
  x.rig = rigNodes(c);
  x.dominated.resize(c.nodes.size());
  for (size_t i = 0; i < pose.positions.size(); ++i)
    x.dominated[size_t(pose.dominantNode[i])].push_back(pose.positions[i]);
  FitResult result;
  markActiveJoints(x, result.report);
  const std::vector<int> owner = mergeSmallBones(x, result.report);
  std::vector<std::vector<glm::vec3>> fitted(c.nodes.size());
  for (size_t j = 0; j < c.nodes.size(); ++j)
    if (x.active[j] && owner[j] >= 0) {
      auto& dst = fitted[size_t(owner[j])];
      dst.insert(dst.end(), x.dominated[j].begin(), x.dominated[j].end());
    }
  // Merged joints act like helper bones for the segments' ends.
  for (size_t j = 0; j < c.nodes.size(); ++j)
    if (x.active[j] && owner[j] != int(j)) x.active[j] = 0;

  std::vector<Candidate> cands;
  for (size_t j = 0; j < c.nodes.size(); ++j)
    if (x.active[j]) fitJointSegments(x, int(j), fitted[j], cands, result.report);
  if (cands.empty()) return Error{name + ": no bone dominates any vertex; cannot fit a stand-in"};
  buildSegments(x, cands, result.standin);
  result.report.segments = result.standin.segments.size();
  if (settings.measure)
    measureAndRepair(x, owner, result);
  else
    result.report.diagonal = x.diag;
  result.report.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace animorph
