#include "core/standin_morph/skeleton_correspondence.h"

#include <algorithm>
#include <cmath>

#include "core/animorphosis/assignment.h"
#include "core/rig/pose.h"

namespace animorph {

namespace {

// Parameter (0..1 along the chain's arc length) of the chain's closest point to x, from rest-pose segments.
float paramOfClosest(const SkeletonChain& ch, const std::vector<PosedSegment>& rest, const glm::vec3& x) {
  float best = 1e30f, param = 1.0f;
  for (size_t k = 0; k < ch.segments.size(); ++k) {
    const PosedSegment& s = rest[size_t(ch.segments[k])];
    const glm::vec3 d = s.b - s.a;
    const float len2 = glm::dot(d, d);
    const float f = len2 > 0.0f ? std::clamp(glm::dot(x - s.a, d) / len2, 0.0f, 1.0f) : 0.0f;
    const float dist = glm::length(s.a + f * d - x);
    if (dist < best) best = dist, param = ch.from[k] + f * (ch.to[k] - ch.from[k]);
  }
  return param;
}

// The segment of ch (index into ch.segments) whose interval holds t.
size_t segmentAt(const SkeletonChain& ch, float t) {
  for (size_t k = 0; k < ch.segments.size(); ++k)
    if (t <= ch.to[k]) return k;
  return ch.segments.size() - 1;
}

glm::vec3 pointAt(const SkeletonChain& ch, const std::vector<PosedSegment>& posed, float t, float& radius,
                  float& weight) {
  const size_t k = segmentAt(ch, t);
  const PosedSegment& s = posed[size_t(ch.segments[k])];
  const float span = ch.to[k] - ch.from[k];
  const float f = span > 0.0f ? std::clamp((t - ch.from[k]) / span, 0.0f, 1.0f) : 0.5f;
  radius = s.radius;
  weight = s.weightScale;
  return s.a + f * (s.b - s.a);
}

}  // namespace

SkeletonChains skeletonChains(const Character& c, const Standin& s) {
  SkeletonChains out;
  const int nodeCount = static_cast<int>(c.nodes.size());
  out.chainOfSegment.assign(s.segments.size(), -1);
  std::vector<std::vector<int>> segsOf(static_cast<size_t>(nodeCount));
  for (size_t i = 0; i < s.segments.size(); ++i)
    if (s.segments[i].node >= 0 && s.segments[i].node < nodeCount) segsOf[size_t(s.segments[i].node)].push_back(int(i));
  // The tree of nodes with segments: parent = nearest ancestor with segments.
  std::vector<std::vector<int>> children(static_cast<size_t>(nodeCount));
  std::vector<int> roots;
  for (int n = 0; n < nodeCount; ++n) {
    if (segsOf[size_t(n)].empty()) continue;
    int p = c.nodes[size_t(n)].parent;
    for (int guard = 0; p >= 0 && segsOf[size_t(p)].empty() && guard < nodeCount; ++guard) p = c.nodes[size_t(p)].parent;
    if (p >= 0 && !segsOf[size_t(p)].empty()) children[size_t(p)].push_back(n);
    else roots.push_back(n);
  }
  const std::vector<glm::mat4> globals = poseGlobals(c, nullptr, 0.0f);
  const std::vector<PosedSegment> rest = poseStandin(s, globals, glm::mat4(1.0f));
  // Chains: from a root or a child of a branch joint, on while a joint has exactly one child.
  struct Start {
    int node, parentChain;
  };
  std::vector<Start> pending;
  for (int r : roots) pending.push_back({r, -1});
  while (!pending.empty()) {
    const Start st = pending.back();
    pending.pop_back();
    SkeletonChain ch;
    ch.parent = st.parentChain;
    ch.name = c.nodes[size_t(st.node)].name;
    int n = st.node;
    for (;;) {
      ch.nodes.push_back(n);
      for (int seg : segsOf[size_t(n)]) ch.segments.push_back(seg);
      if (children[size_t(n)].size() != 1) break;
      n = children[size_t(n)][0];
    }
    const int id = static_cast<int>(out.chains.size());
    for (int seg : ch.segments) out.chainOfSegment[size_t(seg)] = id;
    for (int child : children[size_t(n)]) pending.push_back({child, id});
    out.chains.push_back(std::move(ch));
  }
  if (out.chains.empty()) return out;
  // Arc length intervals, and the features.
  float total = 0.0f;
  std::vector<float> lengths(out.chains.size(), 0.0f);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (size_t i = 0; i < out.chains.size(); ++i) {
    SkeletonChain& ch = out.chains[i];
    float acc = 0.0f;
    for (int seg : ch.segments) {
      const PosedSegment& r = rest[size_t(seg)];
      const float len = std::max(glm::length(r.b - r.a), kMinSegmentLength);
      ch.from.push_back(acc);
      acc += len;
      ch.to.push_back(acc);
      lo = glm::min(lo, glm::min(r.a, r.b));
      hi = glm::max(hi, glm::max(r.a, r.b));
    }
    for (size_t k = 0; k < ch.segments.size(); ++k) ch.from[k] /= acc, ch.to[k] /= acc;
    ch.to.back() = 1.0f;
    lengths[i] = acc;
    total += acc;
  }
  // Sub-tree sizes: children come after their parent in out.chains.
  std::vector<size_t> below(out.chains.size(), 0);
  for (size_t i = out.chains.size(); i-- > 0;) {
    below[i] += out.chains[i].segments.size();
    if (out.chains[i].parent >= 0) below[size_t(out.chains[i].parent)] += below[i];
  }
  for (size_t i = 0; i < out.chains.size(); ++i)
    if (out.chains[i].parent < 0 && (out.mainRoot < 0 || below[i] > below[size_t(out.mainRoot)]))
      out.mainRoot = static_cast<int>(i);
  const glm::vec3 root = glm::vec3(globals[size_t(out.chains[size_t(out.mainRoot)].nodes[0])][3]);
  const float size = std::max(glm::length(hi - lo), 1e-6f);
  for (size_t i = 0; i < out.chains.size(); ++i) {
    SkeletonChain& ch = out.chains[i];
    ch.length = total > 0.0f ? lengths[i] / total : 0.0f;
    ch.subtree = float(below[i]) / float(std::max<size_t>(1, s.segments.size()));
    glm::vec3 centroid(0.0f);
    float mass = 0.0f;
    for (int seg : ch.segments) {
      const PosedSegment& r = rest[size_t(seg)];
      const float m = std::max(glm::length(r.b - r.a), kMinSegmentLength);
      centroid += m * 0.5f * (r.a + r.b);
      mass += m;
    }
    centroid /= mass;
    const glm::vec3 d = centroid - root;
    ch.side = std::abs(d.x) < 0.05f * size ? 0 : (d.x > 0.0f ? 1 : -1);
    ch.direction = glm::length(d) > 0.05f * size ? glm::normalize(d) : glm::vec3(0.0f);
    if (ch.parent >= 0) {
      const glm::vec3 start = glm::vec3(globals[size_t(ch.nodes[0])][3]);
      ch.attach = paramOfClosest(out.chains[size_t(ch.parent)], rest, start);
    }
  }
  return out;
}

float chainMatchCost(const SkeletonChain& a, const SkeletonChain& b) {
  const float side = 0.5f * float(std::abs(a.side - b.side));
  const bool bothCentral = glm::dot(a.direction, a.direction) == 0.0f && glm::dot(b.direction, b.direction) == 0.0f;
  const float direction = bothCentral ? 0.0f : 0.5f * (1.0f - glm::dot(a.direction, b.direction));
  return side + direction + 2.0f * std::abs(a.length - b.length) + std::abs(a.subtree - b.subtree);
}

namespace {

// Per source chain in `fixed`: -1 free, kArtistUnmatched, or the target chain an
// artist pair gives it. Returns per source chain its target chain (-1: none):
// the fixed ones as given, the free ones by a minimum-cost assignment over the
// target chains no pair takes. The main roots match each other while both are
// free: any other pairing with either costs more than any real one.
constexpr int kArtistUnmatched = -2;

std::vector<int> assignChains(const SkeletonChains& source, const SkeletonChains& target, const std::vector<int>& fixed) {
  std::vector<int> match(source.chains.size(), -1);
  std::vector<char> taken(target.chains.size(), 0);
  std::vector<int> rows, cols;
  for (size_t r = 0; r < source.chains.size(); ++r) {
    if (fixed[r] >= 0) match[r] = fixed[r], taken[size_t(fixed[r])] = 1;
    else if (fixed[r] == -1) rows.push_back(int(r));
  }
  for (size_t k = 0; k < target.chains.size(); ++k)
    if (!taken[k]) cols.push_back(int(k));
  if (rows.empty() || cols.empty()) return match;
  const bool rootRule = source.mainRoot >= 0 && target.mainRoot >= 0 && fixed[size_t(source.mainRoot)] == -1 &&
                        !taken[size_t(target.mainRoot)];
  constexpr double kForbidden = 100.0;
  const size_t nr = rows.size(), nc = cols.size();
  std::vector<double> cost(nr * nc);
  for (size_t i = 0; i < nr; ++i)
    for (size_t j = 0; j < nc; ++j) {
      const bool rootR = rootRule && rows[i] == source.mainRoot, rootK = rootRule && cols[j] == target.mainRoot;
      cost[i * nc + j] = rootR && rootK ? 0.0
                         : rootR || rootK
                             ? kForbidden
                             : double(chainMatchCost(source.chains[size_t(rows[i])], target.chains[size_t(cols[j])]));
    }
  const std::vector<int> assigned = minCostAssignment(cost, int(nr), int(nc));
  for (size_t i = 0; i < nr; ++i) {
    const int j = assigned[i];
    if (j < 0) continue;
    const int r = rows[i], k = cols[size_t(j)];
    const bool roots = rootRule && r == source.mainRoot && k == target.mainRoot;
    const float cst = chainMatchCost(source.chains[size_t(r)], target.chains[size_t(k)]);
    if (!roots && (cost[i * nc + size_t(j)] >= kForbidden || cst > kMaxChainMatchCost)) continue;
    match[size_t(r)] = k;
  }
  return match;
}

}  // namespace

int chainNamed(const SkeletonChains& chains, const std::string& name) {
  for (size_t i = 0; i < chains.chains.size(); ++i)
    if (chains.chains[i].name == name) return int(i);
  return -1;
}

SkeletonCorrespondence correspondSkeletons(SkeletonChains source, SkeletonChains target,
                                           const std::vector<ChainPair>& pairs) {
  SkeletonCorrespondence c;
  c.source = std::move(source);
  c.target = std::move(target);
  const size_t rows = c.source.chains.size(), cols = c.target.chains.size();
  c.sourceMatch.assign(rows, -1);
  c.targetMatch.assign(cols, -1);
  c.cost.assign(rows, 0.0f);
  c.pinned.assign(rows, 0);
  c.automatic.assign(rows, -1);
  if (rows == 0 || cols == 0) return c;
  // The artist's pairs, in order; one that cannot apply is skipped with its reason.
  std::vector<int> fixed(rows, -1), pairOfTarget(cols, -1);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const ChainPair& p = pairs[i];
    const std::string where = "chain_pairs[" + std::to_string(i) + "]";
    const int r = chainNamed(c.source, p.source);
    if (r < 0) {
      c.warnings.push_back(where + ".source: no source chain starts at joint '" + p.source + "': pair ignored");
      continue;
    }
    if (fixed[size_t(r)] != -1) {
      c.warnings.push_back(where + ".source: chain '" + p.source + "' is paired by an earlier entry: pair ignored");
      continue;
    }
    if (!p.target) {
      fixed[size_t(r)] = kArtistUnmatched;
      continue;
    }
    const int k = chainNamed(c.target, *p.target);
    if (k < 0) {
      c.warnings.push_back(where + ".target: no target chain starts at joint '" + *p.target + "': pair ignored");
      continue;
    }
    if (pairOfTarget[size_t(k)] >= 0) {
      c.warnings.push_back(where + ".target: chain '" + *p.target + "' is already paired with '" +
                           c.source.chains[size_t(pairOfTarget[size_t(k)])].name + "': pair ignored");
      continue;
    }
    fixed[size_t(r)] = k;
    pairOfTarget[size_t(k)] = r;
  }
  c.sourceMatch = assignChains(c.source, c.target, fixed);
  for (size_t r = 0; r < rows; ++r) {
    const int k = c.sourceMatch[r];
    if (k >= 0) {
      c.targetMatch[size_t(k)] = int(r);
      c.cost[r] = chainMatchCost(c.source.chains[r], c.target.chains[size_t(k)]);
    }
    c.pinned[r] = fixed[r] != -1;
    if (!c.pinned[r]) {
      c.automatic[r] = k;
      continue;
    }
    std::vector<int> without = fixed;
    without[r] = -1;
    c.automatic[r] = assignChains(c.source, c.target, without)[r];
  }
  return c;
}

SegmentImage segmentImage(const SkeletonChains& from, int segment, const SkeletonChains& onto,
                          const std::vector<int>& match, const std::vector<PosedSegment>& ontoPosed, float ownRadius) {
  SegmentImage img;
  const int chain = segment >= 0 && size_t(segment) < from.chainOfSegment.size() ? from.chainOfSegment[size_t(segment)] : -1;
  if (chain < 0 || onto.chains.empty()) return img;
  const SkeletonChain& ch = from.chains[size_t(chain)];
  const int m = match[size_t(chain)];
  if (m >= 0) {
    // Onto the matched chain's segment covering the middle of this segment's interval.
    const size_t k = size_t(std::find(ch.segments.begin(), ch.segments.end(), segment) - ch.segments.begin());
    const float t0 = ch.from[k], t1 = ch.to[k];
    const SkeletonChain& other = onto.chains[size_t(m)];
    const size_t j = segmentAt(other, 0.5f * (t0 + t1));
    const PosedSegment& s = ontoPosed[size_t(other.segments[j])];
    const float span = other.to[j] - other.from[j];
    auto frac = [&](float t) { return span > 0.0f ? std::clamp((t - other.from[j]) / span, 0.0f, 1.0f) : 0.5f; };
    img.a = s.a + frac(t0) * (s.b - s.a);
    img.b = s.a + frac(t1) * (s.b - s.a);
    img.radius = s.radius;
    img.weightScale = s.weightScale;
    return img;
  }
  // Unmatched: onto the point where the chain (or its unmatched ancestors) branches off the nearest matched ancestor.
  int c = chain;
  float attach = 0.0f;
  while (c >= 0 && match[size_t(c)] < 0) {
    attach = from.chains[size_t(c)].attach;
    c = from.chains[size_t(c)].parent;
  }
  const SkeletonChain& other = onto.chains[size_t(c >= 0 ? match[size_t(c)] : onto.mainRoot)];
  float r = 0.0f, wgt = 0.0f;
  img.a = img.b = pointAt(other, ontoPosed, c >= 0 ? attach : 0.0f, r, wgt);
  img.radius = ownRadius;  // measured: keeping the radius changes the volume least per frame (docs/morph.md)
  img.weightScale = wgt;
  return img;
}

}  // namespace animorph
