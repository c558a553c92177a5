#include "standin/fit_standin.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "field/skeleton.h"
#include "standin/character_pose.h"

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
  for (const auto& p : cd.pts) {
    size_t best = 0;
    float bd = INFINITY;
    for (size_t k = 0; k < parts.size(); ++k) {
      const float d = glm::length(p - closestOnSegment(p, parts[k].a, parts[k].b));
      if (d < bd) { bd = d; best = k; }
    }
    parts[best].dist.push_back(bd);
    parts[best].pts.push_back(p);
  }
  for (auto& c : parts)
    if (!c.dist.empty()) out.push_back(std::move(c));
}

const AnimationClip* pickClip(const Character& c, int clip) {
  return clip >= 0 && clip < static_cast<int>(c.clips.size()) ? &c.clips[size_t(clip)] : nullptr;
}

}  // namespace

FitReport measureStandinFit(const Character& c, const Standin& s, const FitSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  FitReport r;
  r.segments = s.segments.size();
  const CharacterPose pose = poseCharacter(c, pickClip(c, settings.clip), settings.clipTimeSec, glm::mat4(1.0f));
  Bounds box;
  for (const auto& p : pose.positions) box.add(p);
  r.diagonal = box.diagonal();
  const auto segs = poseStandin(s, pose.globals, glm::mat4(1.0f));
  const FieldProgram prog = standinProgram(s.kind, s.sharpness, segs);
  std::vector<glm::vec3> out(pose.positions.size());
  r.projection = projectOntoField(prog, segs, pose.positions.data(), pose.positions.size(), out.data(), nullptr,
                                  settings.projection);
  const double diag = std::max(1e-12, r.diagonal);
  r.meanError = r.projection.meanDistance / diag;
  r.maxError = r.projection.maxDistance / diag;
  r.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

Result<FitResult> fitStandin(const Character& c, const FitSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string name = c.sourcePath.empty() ? std::string("character") : c.sourcePath;
  if (settings.clip >= static_cast<int>(c.clips.size()))
    return Error{name + ": clip " + std::to_string(settings.clip) + " does not exist (" +
                 std::to_string(c.clips.size()) + " clips)"};
  const CharacterPose pose = poseCharacter(c, pickClip(c, settings.clip), settings.clipTimeSec, glm::mat4(1.0f));
  if (pose.positions.empty()) return Error{name + ": no mesh vertices to fit a stand-in to"};
  Bounds box;
  for (const auto& p : pose.positions) box.add(p);
  const float diag = std::max(1e-6f, box.diagonal());
  const float minLen = 1e-3f * diag;

  const std::vector<char> rig = rigNodes(c);
  std::vector<std::vector<glm::vec3>> dominated(c.nodes.size());
  for (size_t i = 0; i < pose.positions.size(); ++i) dominated[size_t(pose.dominantNode[i])].push_back(pose.positions[i]);
  auto jointPos = [&](int n) { return glm::vec3(pose.globals[size_t(n)][3]); };
  auto rigParent = [&](int n) {
    int p = c.nodes[size_t(n)].parent;
    while (p >= 0 && !rig[size_t(p)]) p = c.nodes[size_t(p)].parent;
    return p;
  };

  FitResult result;
  std::vector<Candidate> cands;
  for (size_t j = 0; j < c.nodes.size(); ++j) {
    if (!rig[j]) continue;
    const auto& pts = dominated[j];
    if (pts.empty()) {
      ++result.report.bonesOmitted;
      continue;
    }
    const glm::vec3 P = jointPos(int(j));
    std::vector<Candidate> mine;
    for (int ch : c.nodes[j].children) {
      if (!rig[size_t(ch)]) continue;
      const glm::vec3 Q = jointPos(ch);
      if (glm::length(Q - P) > minLen) mine.emplace_back(int(j), P, Q);
    }
    if (mine.empty()) {
      // Leaf (or every child at the joint itself): along the parent bone's
      // direction, else along the dominated vertices' principal axis.
      const int par = rigParent(int(j));
      glm::vec3 dir(0.0f);
      if (par >= 0 && glm::length(P - jointPos(par)) > minLen) dir = glm::normalize(P - jointPos(par));
      std::vector<float> u;
      if (glm::length(dir) > 0.0f) {
        for (const auto& p : pts) u.push_back(glm::dot(p - P, dir));
        const float far = percentile(u, 0.9f);
        if (far > minLen) {
          Candidate cd{int(j), P, P + dir * far};
          cd.shrinkB = true;
          mine.push_back(cd);
        }
      }
      if (mine.empty()) {
        glm::vec3 centroid;
        const glm::vec3 axis = principalAxis(pts, centroid);
        u.clear();
        for (const auto& p : pts) u.push_back(glm::dot(p - centroid, axis));
        std::vector<float> u2 = u;
        float lo = percentile(u, 0.1f), hi = percentile(u2, 0.9f);
        if (hi - lo < minLen) { lo -= 0.5f * minLen; hi += 0.5f * minLen; }
        Candidate cd{int(j), centroid + axis * lo, centroid + axis * hi};
        cd.shrinkA = cd.shrinkB = true;
        mine.push_back(cd);
        result.report.notes.push_back("node '" + c.nodes[j].name + "': no child bone; segment along its vertices' principal axis");
      }
    }
    // Each dominated vertex belongs to its closest segment of this bone.
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
    std::vector<Candidate> split;
    for (auto& cd : mine)
      if (!cd.dist.empty()) splitFlat(cd, minLen, split);
    for (auto& cd : split) {
      cd.radius = std::max(1e-3f * diag, percentile(cd.dist, settings.radiusPercentile));
      cd.pts.clear();
      cd.pts.shrink_to_fit();
      cands.push_back(std::move(cd));
    }
  }
  if (cands.empty()) return Error{name + ": no bone dominates any vertex; cannot fit a stand-in"};

  std::vector<float> radii;
  for (const auto& cd : cands) radii.push_back(cd.radius);
  const float medianR = percentile(radii, 0.5f);
  Standin& s = result.standin;
  s.kind = settings.kind;
  s.sharpness = settings.sharpnessTimesRadius / std::max(1e-6f, medianR);
  for (auto& cd : cands) {
    // Free ends pull in by half a radius: the surface reaches past a segment's end.
    glm::vec3 d = cd.b - cd.a;
    const float len = glm::length(d);
    if (len > 0.0f) {
      d /= len;
      float room = len - minLen;
      float pull = std::min(0.5f * cd.radius, room * 0.5f);
      if (pull > 0.0f) {
        if (cd.shrinkA) cd.a += d * pull;
        if (cd.shrinkB) cd.b -= d * pull;
      }
    }
    const glm::mat4 inv = glm::inverse(pose.globals[size_t(cd.node)]);
    StandinSegment seg;
    seg.node = cd.node;
    seg.a = glm::vec3(inv * glm::vec4(cd.a, 1.0f));
    seg.b = glm::vec3(inv * glm::vec4(cd.b, 1.0f));
    // Radii are stored in the node's space too (poseStandin scales them back).
    const glm::mat3 l(pose.globals[size_t(cd.node)]);
    const float sc = (glm::length(l[0]) + glm::length(l[1]) + glm::length(l[2])) / 3.0f;
    seg.radius = cd.radius / std::max(1e-12f, sc);
    s.segments.push_back(seg);
  }
  result.report.segments = s.segments.size();
  if (settings.measure) {
    FitReport m = measureStandinFit(c, s, settings);
    result.report.diagonal = m.diagonal;
    result.report.meanError = m.meanError;
    result.report.maxError = m.maxError;
    result.report.projection = m.projection;
  } else {
    result.report.diagonal = diag;
  }
  result.report.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace animorph
