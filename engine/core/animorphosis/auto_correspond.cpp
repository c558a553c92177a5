#include "core/animorphosis/auto_correspond.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <numeric>
#include <unordered_set>

#include <glm/gtc/quaternion.hpp>

#include "core/animorphosis/assignment.h"
#include "core/animorphosis/match_side.h"
#include "core/animorphosis/validate_correspondence.h"

namespace animorph {

namespace {

enum class Family { Primitive, Group, Map, Other };

Family familyOf(NodeType t) {
  if (t <= NodeType::Capsule || t == NodeType::CoonsPatch) return Family::Primitive;
  if (t == NodeType::Blend || t == NodeType::Union || t == NodeType::HyperBlend || t == NodeType::SplineOfNodes)
    return Family::Group;
  if (t >= NodeType::Frame && t <= NodeType::Bend) return Family::Map;
  return Family::Other;
}

double kindCost(NodeType x, NodeType y) {
  if (x == y) return 0.0;
  // A spline of nodes is a chain of copies written short: a blend of them is nearly its kind.
  if ((x == NodeType::SplineOfNodes && y == NodeType::Blend) || (y == NodeType::SplineOfNodes && x == NodeType::Blend))
    return 0.25;
  // Blend, union and hyper-blend bridge into each other (a hyper-blend in between).
  auto bridged = [](NodeType t) { return t == NodeType::Blend || t == NodeType::Union || t == NodeType::HyperBlend; };
  if (bridged(x) && bridged(y)) return 0.25;
  Family f = familyOf(x);
  return f == familyOf(y) && f != Family::Other ? 0.5 : 1.0;
}

// Columns costed per row on levels wider than the Hungarian method's limit.
constexpr int kWideCandidates = 12;

bool isSplitPart(NodeType t) { return familyOf(t) == Family::Primitive; }

// A group whose children the matcher may take one by one (regrouped children).
bool isOpenableGroup(const BlobNode& n) {
  return n.children.size() >= 2 && (n.type == NodeType::Blend || n.type == NodeType::Union || n.type == NodeType::HyperBlend);
}

// What a candidate is compared by: its extents over the clip (possibly merged from several
// nodes), its kind and its primitive count.
struct Shape {
  std::vector<NodeExtent> extents;
  std::vector<NodeType> types;  // the kinds along its chain, bottom first: the closest pair of kinds counts
  float primitives = 0.0f;
};

double kindCost(const Shape& x, const Shape& y) {
  double best = 1.0;
  for (NodeType a : x.types)
    for (NodeType b : y.types) best = std::min(best, kindCost(a, b));
  return best;
}

// The shape of one item (its chain's kinds, its bottom's extents), or of several merged (their
// kinds, the first's chain).
Shape shapeOf(const MatchSide& s, const std::vector<int>& slots, int chainTop = -1) {
  Shape r;
  r.extents.assign(size_t(s.samples()), NodeExtent{});
  r.types.push_back(s.node(slots.front()).type);
  for (int c = chainTop; c >= 0 && c != slots.front(); c = s.children(c).front()) r.types.push_back(s.node(c).type);
  for (int slot : slots) {
    const NodeExtent* e = s.extents(slot);
    for (int k = 0; k < s.samples(); ++k) r.extents[size_t(k)].merge(e[k]);
    r.primitives += s.primitives(slot);
  }
  return r;
}

double relativeDifference(double x, double y) { return std::abs(x - y) / std::max({x, y, 1.0}); }

struct Matcher {
  const MatchSide& A;
  const MatchSide& B;
  const AutoCorrespondSettings& st;
  int samples;

  Matcher(const MatchSide& a, const MatchSide& b, const AutoCorrespondSettings& s)
      : A(a), B(b), st(s), samples(std::min(a.samples(), b.samples())) {}

  // Sample k of a side with `own` samples, read at the common sample count (both sample their
  // clip at the same fractions when they have as many samples).
  static int at(int k, int own, int common) { return own == common ? k : k * own / common; }

  // Cost of pairing x (in A, under the matched parent pa) with y (in B, under pb). shift (one per
  // sample, or null): what the level's consensus says A's offsets are off by (Level::recentre).
  double cost(const Shape& x, int pa, const Shape& y, int pb, const glm::vec3* shift = nullptr) const {
    const NodeExtent* ea = A.extents(pa);
    const NodeExtent* eb = B.extents(pb);
    double pos = 0.0, size = 0.0;
    for (int k = 0; k < samples; ++k) {
      const NodeExtent& xa = x.extents[size_t(at(k, A.samples(), samples))];
      const NodeExtent& yb = y.extents[size_t(at(k, B.samples(), samples))];
      const NodeExtent& pA = ea[at(k, A.samples(), samples)];
      const NodeExtent& pB = eb[at(k, B.samples(), samples)];
      glm::vec3 oa = xa.count > 0 ? (xa.centroid() - pA.centroid()) / A.scale() : glm::vec3(0.0f);
      glm::vec3 ob = yb.count > 0 ? (yb.centroid() - pB.centroid()) / B.scale() : glm::vec3(0.0f);
      if (shift) oa -= shift[k];
      pos += glm::distance(oa, ob);
      size += glm::distance(xa.size() / A.scale(), yb.size() / B.scale());
    }
    return st.kindWeight * kindCost(x, y) + st.positionWeight * pos / samples +
           st.sizeWeight * size / samples + st.hierarchyWeight * relativeDifference(x.primitives, y.primitives);
  }
};

// One level: the items (chains) under a matched pair of A and B, and how they were paired.
struct LevelMatch {
  std::vector<int> xs, ys;  // item indices; one of them has one entry (a split has several on the other side)
  double cost = 0.0;
  float confidence = 0.0f;
};

class Level {
 public:
  Level(const Matcher& m, int pa, int pb, std::vector<ChainItem> xs, std::vector<ChainItem> ys)
      : m_(m), pa_(pa), pb_(pb), xs_(std::move(xs)), ys_(std::move(ys)) {
    parentScale_ = std::clamp(double(glm::length(m.A.extents(pa)[0].size())) / m.A.scale(), 0.01, 1.0);
  }

  // Matches the items; opens groups that match better as their parts; proposes splits.
  std::vector<LevelMatch> run(int* regrouped, int* splits);
  const std::vector<ChainItem>& xs() const { return xs_; }
  // The final assignment's score after run() (each item pays its pair's cost, or maxCost unpaired).
  double score() const { return score_; }
  const std::vector<ChainItem>& ys() const { return ys_; }

 private:
  void fillCosts();
  std::vector<int> assign() const;
  double score(const std::vector<int>& match) const;
  bool tryOpen(bool sideA, size_t item, std::vector<int>& match, double& best);
  std::vector<LevelMatch> collect(const std::vector<int>& match, int* splits) const;
  double regretOf(const std::vector<int>& rowOf, int r, int c) const;
  bool trySplit(bool sideA, int one, std::vector<int> candidates, LevelMatch& out) const;
  double pairCost(int x, int y) const { return c_[size_t(x) * ys_.size() + size_t(y)]; }
  // Costs and assigns the level again without its consensus offset (the median offset difference
  // of its pairs); kept when it scores better. False when it was not.
  bool recentre(std::vector<int>& match, double& best);
  // Whether some item of A, of B, is left unpaired (or paired above maxCost) by match.
  void findUnpaired(const std::vector<int>& match, bool& unpairedA, bool& unpairedB) const;
  const glm::vec3* shift() const { return shift_.empty() ? nullptr : shift_.data(); }

  const Matcher& m_;
  int pa_, pb_;
  std::vector<ChainItem> xs_, ys_;
  std::vector<Shape> sx_, sy_;
  std::vector<double> c_;
  double parentScale_ = 1.0;  // the parent's size in units of its tree's
  std::vector<glm::vec3> shift_;  // per sample: the level's consensus offset of A against B (empty: none)
  double score_ = 0.0;
};

void Level::fillCosts() {
  sx_.clear();
  sy_.clear();
  for (const ChainItem& x : xs_) sx_.push_back(shapeOf(m_.A, {x.bottom}, x.top));
  for (const ChainItem& y : ys_) sy_.push_back(shapeOf(m_.B, {y.bottom}, y.top));
  const size_t cols = ys_.size();
  if (std::max(xs_.size(), cols) <= size_t(m_.st.hungarianLimit)) {
    c_.assign(xs_.size() * cols, 0.0);
    for (size_t r = 0; r < xs_.size(); ++r)
      for (size_t c = 0; c < cols; ++c) c_[r * cols + c] = m_.cost(sx_[r], pa_, sy_[c], pb_, shift());
    return;
  }
  // A wide level (a union of thousands of patches): each row is costed against its nearest columns
  // only (by offset from the parents at the first sample); the others stay above maxCost.
  const double unreachable = 2.0 * m_.st.maxCost;
  c_.assign(xs_.size() * cols, unreachable);
  const glm::vec3 pa = m_.A.extents(pa_)[0].centroid(), pb = m_.B.extents(pb_)[0].centroid();
  std::vector<glm::vec3> ob(cols);
  for (size_t c = 0; c < cols; ++c) ob[c] = (sy_[c].extents[0].centroid() - pb) / m_.B.scale();
  std::vector<std::pair<float, int>> near(cols);
  const size_t keep = std::min(cols, size_t(kWideCandidates));
  for (size_t r = 0; r < xs_.size(); ++r) {
    const glm::vec3 oa = (sx_[r].extents[0].centroid() - pa) / m_.A.scale();
    for (size_t c = 0; c < cols; ++c) near[c] = {glm::distance(oa, ob[c]), int(c)};
    std::nth_element(near.begin(), near.begin() + long(keep) - 1, near.end());
    for (size_t k = 0; k < keep; ++k)
      c_[r * cols + size_t(near[k].second)] = m_.cost(sx_[r], pa_, sy_[size_t(near[k].second)], pb_);
  }
}

std::vector<int> Level::assign() const {
  const int rows = int(xs_.size()), cols = int(ys_.size());
  // Costs are capped just above maxCost: a pair that will not be linked anyway must not pull the
  // assignment of the others.
  const double cap = m_.st.maxCost * 1.000001;
  std::vector<double> capped(c_.size());
  for (size_t i = 0; i < c_.size(); ++i) capped[i] = std::min(cap, c_[i]);
  if (std::max(rows, cols) <= m_.st.hungarianLimit) return minCostAssignment(capped, rows, cols);
  // Greedy, cheapest pair first: with distinct positions the nearest pairs are the right ones.
  // Only pairs that could be linked take part (fillCosts costed each row's nearest columns).
  std::vector<std::pair<double, size_t>> order;
  for (size_t i = 0; i < capped.size(); ++i)
    if (capped[i] < cap) order.push_back({capped[i], i});
  std::sort(order.begin(), order.end());
  std::vector<int> match(size_t(rows), -1);
  std::vector<char> taken(size_t(cols), 0);
  for (const auto& [cost, k] : order) {
    int r = int(k / size_t(cols)), c = int(k % size_t(cols));
    if (match[size_t(r)] < 0 && !taken[size_t(c)]) match[size_t(r)] = c, taken[size_t(c)] = 1;
  }
  return match;
}

// Lower is better: each item of either side pays its pair's cost, or maxCost when it stays unpaired.
double Level::score(const std::vector<int>& match) const {
  double s = 0.0;
  std::vector<char> used(ys_.size(), 0);
  for (size_t r = 0; r < xs_.size(); ++r) {
    int c = match[r];
    if (c >= 0 && pairCost(int(r), c) <= m_.st.maxCost) {
      s += 2.0 * pairCost(int(r), c);
      used[size_t(c)] = 1;
    } else {
      s += m_.st.maxCost;
    }
  }
  for (char u : used) s += u ? 0.0 : m_.st.maxCost;
  return s;
}

// Replaces a group item by its children's items when that pairs the level better.
bool Level::tryOpen(bool sideA, size_t item, std::vector<int>& match, double& best) {
  std::vector<ChainItem>& list = sideA ? xs_ : ys_;
  const MatchSide& side = sideA ? m_.A : m_.B;
  if (!isOpenableGroup(side.node(list[item].bottom))) return false;
  std::vector<ChainItem> saved = list;
  std::vector<ChainItem> inner = side.items(list[item].bottom);
  list.erase(list.begin() + long(item));
  list.insert(list.end(), inner.begin(), inner.end());
  fillCosts();
  std::vector<int> trial = assign();
  double s = score(trial);
  // Opening adds items: it must pay for itself clearly, not by the extra items' own cost.
  if (s < best - 0.25 * m_.st.maxCost) {
    best = s;
    match = std::move(trial);
    return true;
  }
  list = std::move(saved);
  fillCosts();
  return false;
}

// A part dropped, added or split moves its parent's centroid, and with it every sibling's offset:
// siblings that did not change then all differ by the same vector. The median difference of the
// paired items (per sample, per axis) is that vector; the level is costed and assigned again
// without it, and kept so when it pairs the level better.
bool Level::recentre(std::vector<int>& match, double& best) {
  if (std::max(xs_.size(), ys_.size()) > size_t(m_.st.hungarianLimit)) return false;
  std::vector<std::pair<int, int>> pairs;
  for (size_t r = 0; r < xs_.size(); ++r)
    if (match[r] >= 0 && pairCost(int(r), match[r]) <= m_.st.maxCost) pairs.push_back({int(r), match[r]});
  if (pairs.size() < 2) return false;
  const int n = m_.samples;
  std::vector<glm::vec3> shift(static_cast<size_t>(n), glm::vec3(0.0f));
  const NodeExtent* ea = m_.A.extents(pa_);
  const NodeExtent* eb = m_.B.extents(pb_);
  std::vector<float> d(pairs.size());
  for (int k = 0; k < n; ++k) {
    const int ka = Matcher::at(k, m_.A.samples(), n), kb = Matcher::at(k, m_.B.samples(), n);
    for (int axis = 0; axis < 3; ++axis) {
      for (size_t i = 0; i < pairs.size(); ++i) {
        const NodeExtent& x = sx_[size_t(pairs[i].first)].extents[size_t(ka)];
        const NodeExtent& y = sy_[size_t(pairs[i].second)].extents[size_t(kb)];
        d[i] = (x.centroid()[axis] - ea[ka].centroid()[axis]) / m_.A.scale() -
               (y.centroid()[axis] - eb[kb].centroid()[axis]) / m_.B.scale();
      }
      std::nth_element(d.begin(), d.begin() + long(d.size() / 2), d.end());
      float med = d[d.size() / 2];
      if (d.size() % 2 == 0) med = 0.5f * (med + *std::max_element(d.begin(), d.begin() + long(d.size() / 2)));
      shift[size_t(k)][axis] = med;
    }
  }
  std::vector<glm::vec3> saved = std::move(shift_);
  shift_ = std::move(shift);
  fillCosts();
  std::vector<int> trial = assign();
  const double s = score(trial);
  if (s < best) {
    best = s;
    match = std::move(trial);
    return true;
  }
  shift_ = std::move(saved);
  fillCosts();
  return false;
}

void Level::findUnpaired(const std::vector<int>& match, bool& unpairedA, bool& unpairedB) const {
  std::vector<char> usedB(ys_.size(), 0);
  unpairedA = unpairedB = false;
  for (size_t r = 0; r < xs_.size(); ++r) {
    const bool paired = match[r] >= 0 && pairCost(int(r), match[r]) <= m_.st.maxCost;
    if (paired) usedB[size_t(match[r])] = 1;
    unpairedA = unpairedA || !paired;
  }
  for (char u : usedB) unpairedB = unpairedB || !u;
}

std::vector<LevelMatch> Level::run(int* regrouped, int* splits) {
  fillCosts();
  std::vector<int> match = assign();
  double best = score(match);
  // Groups paired at a high cost or not at all may be regrouped children: try opening them up
  // (a group opened may hold another).
  for (int round = 0; round < 16; ++round) {
    bool opened = false;
    // A group that pairs cheaply may still hold items the other side left unpaired (parts moved
    // into a new group with the bundle they sit on match the bundle alone): it is tried too.
    bool unpairedA = false, unpairedB = false;
    findUnpaired(match, unpairedA, unpairedB);
    for (int sideA = 0; sideA < 2 && !opened; ++sideA) {
      const size_t n = sideA ? xs_.size() : ys_.size();
      const bool othersLeft = sideA ? unpairedB : unpairedA;
      for (size_t i = 0; i < n && !opened; ++i) {
        double paired = std::numeric_limits<double>::infinity();
        if (sideA) {
          if (match[i] >= 0) paired = pairCost(int(i), match[i]);
        } else {
          for (size_t r = 0; r < xs_.size(); ++r)
            if (match[r] == int(i)) paired = pairCost(int(r), int(i));
        }
        if ((paired > 0.02 * m_.st.maxCost || othersLeft) && tryOpen(sideA != 0, i, match, best)) opened = true;
      }
    }
    if (!opened) break;
    ++*regrouped;
  }
  recentre(match, best);
  score_ = best;
  return collect(match, splits);
}

// A primitive of one side whose shape is that of two or three primitives of the other together.
bool Level::trySplit(bool sideA, int one, std::vector<int> candidates, LevelMatch& out) const {
  const MatchSide& mine = sideA ? m_.A : m_.B;
  const MatchSide& other = sideA ? m_.B : m_.A;
  const std::vector<ChainItem>& parts = sideA ? ys_ : xs_;
  const Shape self = shapeOf(mine, {(sideA ? xs_ : ys_)[size_t(one)].bottom});
  auto costOf = [&](const std::vector<int>& set) {
    std::vector<int> slots;
    for (int c : set) slots.push_back(parts[size_t(c)].bottom);
    Shape merged = shapeOf(other, slots);
    merged.types = self.types;    // the parts' own kinds were compared when they were filtered
    merged.primitives = self.primitives;
    return sideA ? m_.cost(self, pa_, merged, pb_, shift()) : m_.cost(merged, pa_, self, pb_, shift());
  };
  // The nearest candidates only (a limb faces two or three segments next to it).
  const glm::vec3 c0 = self.extents[0].centroid();
  auto distance = [&](int p) { return glm::distance(other.extents(parts[size_t(p)].bottom)[0].centroid(), c0); };
  std::sort(candidates.begin(), candidates.end(), [&](int p, int q) { return distance(p) < distance(q); });
  if (candidates.size() > 4) candidates.resize(4);
  double bestCost = m_.st.splitMaxCost;
  std::vector<int> bestSet;
  const size_t n = candidates.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      std::vector<int> pair{candidates[i], candidates[j]};
      if (double c = costOf(pair); c < bestCost) bestCost = c, bestSet = pair;
      for (size_t k = j + 1; k < n; ++k) {
        std::vector<int> triple{candidates[i], candidates[j], candidates[k]};
        if (double c = costOf(triple); c < bestCost) bestCost = c, bestSet = triple;
      }
    }
  if (bestSet.empty()) return false;
  out = {};
  (sideA ? out.xs : out.ys).push_back(one);
  (sideA ? out.ys : out.xs) = bestSet;
  out.cost = bestCost;
  out.confidence = float(std::clamp(1.0 - bestCost / m_.st.maxCost, 0.0, 1.0));
  return true;
}

// How much dearer the level would be without the pair (r, c), rowOf giving each column's row in
// the assignment: r taking another column (free, or traded with that column's row), c taking a
// free row with r unpaired, or both unpaired; the least of these. Unpaired items cost maxCost.
double Level::regretOf(const std::vector<int>& rowOf, int r, int c) const {
  const double cap = m_.st.maxCost, k = pairCost(r, c);
  auto cost = [&](int x, int y) { return std::min(pairCost(x, y), cap); };
  double best = 2.0 * cap - k;  // both unpaired
  // On a wide level only r's reachable columns are tried (reading the matrix by columns would
  // miss the cache at every step).
  const bool wide = std::max(xs_.size(), ys_.size()) > size_t(m_.st.hungarianLimit);
  for (size_t o = 0; o < ys_.size(); ++o) {
    if (int(o) == c || (wide && pairCost(r, int(o)) >= cap)) continue;
    const int r2 = rowOf[o];
    if (r2 >= 0)
      best = std::min(best, cost(r, int(o)) + cost(r2, c) - k - cost(r2, int(o)));  // r and r2 trade
    else
      best = std::min(best, cost(r, int(o)) - k);  // r takes the free o, c goes unpaired
  }
  if (wide) return std::max(0.0, best);
  std::vector<char> paired(xs_.size(), 0);
  for (int x : rowOf)
    if (x >= 0) paired[size_t(x)] = 1;
  for (size_t o = 0; o < xs_.size(); ++o)
    if (!paired[o]) best = std::min(best, cost(int(o), c) - k);  // a free row takes c, r goes unpaired
  return std::max(0.0, best);
}

// The assignment's pairs with their confidence, then splits among what stayed unpaired.
std::vector<LevelMatch> Level::collect(const std::vector<int>& match, int* splits) const {
  const size_t rows = xs_.size(), cols = ys_.size();
  std::vector<LevelMatch> out;
  std::vector<char> usedX(rows, 0), usedY(cols, 0);
  std::vector<int> rowOf(cols, -1);
  for (size_t i = 0; i < rows; ++i)
    if (match[i] >= 0 && pairCost(int(i), match[i]) <= m_.st.maxCost) rowOf[size_t(match[i])] = int(i);
  for (size_t r = 0; r < rows; ++r) {
    const int c = match[r];
    if (c < 0) continue;
    const double k = pairCost(int(r), c);
    if (k > m_.st.maxCost) continue;
    // How much the next best assignment without this pair would cost more, against the pair's own
    // cost (a close alternative to a good pair matters, to a poor pair less so) and in units of the
    // parent's size (fibres 5 mm apart in an arm 30 cm long are as distinct as limbs 10 cm apart in
    // a body of a metre).
    const double regret = regretOf(rowOf, int(r), c);
    const double distinct = std::clamp(regret / (0.25 * k + m_.st.marginScale * parentScale_), 0.0, 1.0);
    LevelMatch lm;
    lm.xs = {int(r)};
    lm.ys = {c};
    lm.cost = k;
    lm.confidence = float(std::clamp(1.0 - k / m_.st.maxCost, 0.0, 1.0) * distinct);
    out.push_back(lm);
    usedX[r] = usedY[size_t(c)] = 1;
  }
  // A pair whose x is better matched by y together with unpaired neighbours of y: a split.
  for (LevelMatch& lm : out) {
    const int r = lm.xs[0], c = lm.ys[0];
    if (lm.cost <= 0.01 * m_.st.maxCost || !isSplitPart(m_.A.node(xs_[size_t(r)].bottom).type)) continue;
    for (int sideA = 1; sideA >= 0; --sideA) {
      const std::vector<ChainItem>& other = sideA ? ys_ : xs_;
      const std::vector<char>& otherUsed = sideA ? usedY : usedX;
      const MatchSide& os = sideA ? m_.B : m_.A;
      std::vector<int> candidates{sideA ? c : r};
      for (size_t o = 0; o < other.size(); ++o)
        if (!otherUsed[o] && isSplitPart(os.node(other[o].bottom).type)) candidates.push_back(int(o));
      LevelMatch split;
      const bool tried = candidates.size() >= 2 && trySplit(sideA != 0, sideA ? r : c, candidates, split);
      if (!tried || split.cost > 0.5 * lm.cost)
        continue;
      const std::vector<int>& parts = sideA ? split.ys : split.xs;
      if (std::find(parts.begin(), parts.end(), sideA ? c : r) == parts.end()) continue;  // its partner stays in
      for (int o : (sideA ? split.ys : split.xs)) (sideA ? usedY : usedX)[size_t(o)] = 1;
      lm = split;
      ++*splits;
      break;
    }
  }
  for (int sideA = 1; sideA >= 0; --sideA) {
    std::vector<char>& mineUsed = sideA ? usedX : usedY;
    std::vector<char>& otherUsed = sideA ? usedY : usedX;
    const std::vector<ChainItem>& mine = sideA ? xs_ : ys_;
    const std::vector<ChainItem>& other = sideA ? ys_ : xs_;
    const MatchSide& ms = sideA ? m_.A : m_.B;
    const MatchSide& os = sideA ? m_.B : m_.A;
    for (size_t i = 0; i < mine.size(); ++i) {
      if (mineUsed[i] || !isSplitPart(ms.node(mine[i].bottom).type)) continue;
      std::vector<int> candidates;
      for (size_t o = 0; o < other.size(); ++o)
        if (!otherUsed[o] && isSplitPart(os.node(other[o].bottom).type)) candidates.push_back(int(o));
      if (candidates.size() < 2) break;
      LevelMatch lm;
      if (!trySplit(sideA != 0, int(i), candidates, lm)) continue;
      mineUsed[i] = 1;
      for (int o : (sideA ? lm.ys : lm.xs)) otherUsed[size_t(o)] = 1;
      out.push_back(lm);
      ++*splits;
    }
  }
  return out;
}

// Aligns two chains top to bottom, keeping their order: pairs of the same kind score most,
// then of the same family; the bottoms pair whatever they are (the level matched them).
// Frames of similar translation and rotation score a little more, so a chain's own frame
// pairs with its partner rather than with a wrapper. Returns (A slot, B slot) pairs.
std::vector<std::pair<int, int>> alignChains(const MatchSide& A, const std::vector<int>& ca, const MatchSide& B,
                                             const std::vector<int>& cb, double timeA, double timeB) {
  const size_t m = ca.size(), n = cb.size();
  auto pairScore = [&](size_t i, size_t j) -> double {
    const BlobNode& x = A.node(ca[i]);
    const BlobNode& y = B.node(cb[j]);
    const bool bottoms = i + 1 == m && j + 1 == n;
    double s = x.type == y.type ? 1.5 : familyOf(x.type) == familyOf(y.type) ? 1.0 : bottoms ? 0.6 : -1.0;
    if (s < 0.0) return s;
    if (bottoms) s += 0.4;
    if (x.type == NodeType::Frame && y.type == NodeType::Frame) {
      glm::vec3 ta = x.vec3Param("translation").evaluate(timeA) / A.scale();
      glm::vec3 tb = y.vec3Param("translation").evaluate(timeB) / B.scale();
      float dq = std::abs(glm::dot(glm::normalize(x.quatParam("rotation").evaluate(timeA)),
                                   glm::normalize(y.quatParam("rotation").evaluate(timeB))));
      s += 0.6 * std::exp(-glm::distance(ta, tb) / 0.02) + 0.15 * dq * dq;
    }
    return s;
  };
  // best[i][j]: the best score aligning ca[i..] with cb[j..].
  std::vector<double> best((m + 1) * (n + 1), 0.0);
  auto at = [&](size_t i, size_t j) -> double& { return best[i * (n + 1) + j]; };
  for (size_t i = m; i-- > 0;)
    for (size_t j = n; j-- > 0;) {
      double s = std::max(at(i + 1, j), at(i, j + 1));
      double p = pairScore(i, j);
      if (p >= 0.0) s = std::max(s, p + at(i + 1, j + 1));
      at(i, j) = s;
    }
  std::vector<std::pair<int, int>> r;
  for (size_t i = 0, j = 0; i < m && j < n;) {
    double p = pairScore(i, j);
    if (p >= 0.0 && at(i, j) == p + at(i + 1, j + 1)) {
      r.push_back({ca[i], cb[j]});
      ++i, ++j;
    } else if (at(i, j) == at(i + 1, j)) {
      ++i;
    } else {
      ++j;
    }
  }
  return r;
}

// The whole matching: state shared by the levels, and the links as they are found.
class AutoMapper {
 public:
  AutoMapper(const BlobTree& a, const BlobTree& b, const AutoCorrespondSettings& st,
             const std::vector<CorrespondenceLink>& artist)
      : st_(st), A_(a, st.timeSecA, st.clipSamples), B_(b, st.timeSecB, st.clipSamples), m_(A_, B_, st_),
        artist_(artist) {
    for (const auto& l : artist_) {
      artistA_.insert(A_.slotOf(l.nodeA));
      artistB_.insert(B_.slotOf(l.nodeB));
    }
  }

  // Matches every level from the roots down; false when the settings' cancel flag stopped it.
  bool run(AutoCorrespondReport& rep);
  std::vector<CorrespondenceLink> links;  // confidence set; the caller splits them at the threshold

 private:
  struct Pair {
    int a, b;
    float confidence;
  };
  bool agrees(int x, int y) const;
  void link(int x, int y, float confidence);
  void matchBelow(const Pair& p, AutoCorrespondReport& rep);
  void emitChains(const Level& level, const LevelMatch& lm, float parentConfidence);
  std::vector<ChainItem> freeItems(const MatchSide& side, int slot, const std::unordered_set<int>& artist) const;

  const AutoCorrespondSettings& st_;
  MatchSide A_, B_;
  Matcher m_;
  const std::vector<CorrespondenceLink>& artist_;
  std::unordered_set<int> artistA_, artistB_;
  std::deque<Pair> queue_;
};

// An automatic link x -> y must agree with every artist link on what lies inside what.
bool AutoMapper::agrees(int x, int y) const {
  for (const auto& l : artist_) {
    const int la = A_.slotOf(l.nodeA), lb = B_.slotOf(l.nodeB);
    if (A_.below(la, x) != B_.below(lb, y)) return false;
    if (A_.below(x, la) != B_.below(y, lb)) return false;
  }
  return true;
}

void AutoMapper::link(int x, int y, float confidence) {
  if (!agrees(x, y)) return;
  CorrespondenceLink l;
  l.nodeA = A_.node(x).id;
  l.nodeB = B_.node(y).id;
  l.artist = false;
  l.confidence = confidence;
  links.push_back(l);
}

std::vector<ChainItem> AutoMapper::freeItems(const MatchSide& side, int slot, const std::unordered_set<int>& artist) const {
  std::vector<ChainItem> r;
  for (const ChainItem& c : side.items(slot)) {
    bool free = true;
    for (int s : side.chainSlots(c)) free = free && !artist.count(s);
    if (free) r.push_back(c);
  }
  return r;
}

// Links a level's match: a pair aligns its two chains and is matched further below its deepest
// aligned nodes; a split links its bottoms only. Nothing is surer than the link it hangs on.
void AutoMapper::emitChains(const Level& level, const LevelMatch& lm, float parentConfidence) {
  const float conf = std::min(lm.confidence, parentConfidence);
  if (lm.xs.size() == 1 && lm.ys.size() == 1) {
    const ChainItem& x = level.xs()[size_t(lm.xs[0])];
    const ChainItem& y = level.ys()[size_t(lm.ys[0])];
    auto pairs = alignChains(A_, A_.chainSlots(x), B_, B_.chainSlots(y), st_.timeSecA, st_.timeSecB);
    for (const auto& [a, b] : pairs) link(a, b, conf);
    if (!pairs.empty()) queue_.push_back({pairs.back().first, pairs.back().second, conf});
    return;
  }
  for (int xi : lm.xs)
    for (int yi : lm.ys) link(level.xs()[size_t(xi)].bottom, level.ys()[size_t(yi)].bottom, conf);
}

void AutoMapper::matchBelow(const Pair& p, AutoCorrespondReport& rep) {
  const BlobNode& na = A_.node(p.a);
  const BlobNode& nb = B_.node(p.b);
  // A spline of nodes and a group of another kind morph as a whole (one shrinks, the other grows):
  // nothing below them pairs.
  if ((na.type == NodeType::SplineOfNodes) != (nb.type == NodeType::SplineOfNodes)) return;
  // One side in the middle of a chain the other has left: either the rest of that chain wraps what
  // lies below (skip it: a frame over a new group of the other's children), or the other side's node
  // lost children (keep it: a frame left with one child); both are matched, the level that pairs
  // better (Level::score) is kept.
  std::vector<std::pair<int, int>> options{{p.a, p.b}};
  if (isTransparentLink(na) && !isTransparentLink(nb)) options.push_back({A_.chainFrom(p.a).bottom, p.b});
  if (isTransparentLink(nb) && !isTransparentLink(na)) options.push_back({p.a, B_.chainFrom(p.b).bottom});
  std::unique_ptr<Level> best;
  std::vector<LevelMatch> bestMatches;
  int bestRegrouped = 0, bestSplits = 0;
  for (const auto& [ua, ub] : options) {
    std::vector<ChainItem> xs = freeItems(A_, ua, artistA_), ys = freeItems(B_, ub, artistB_);
    if (xs.empty() || ys.empty()) continue;
    auto level = std::make_unique<Level>(m_, ua, ub, std::move(xs), std::move(ys));
    int regrouped = 0, splits = 0;
    std::vector<LevelMatch> matches = level->run(&regrouped, &splits);
    if (best && level->score() >= best->score()) continue;
    best = std::move(level);
    bestMatches = std::move(matches);
    bestRegrouped = regrouped;
    bestSplits = splits;
  }
  if (!best) return;
  rep.regrouped += bestRegrouped;
  rep.splits += bestSplits;
  for (const LevelMatch& lm : bestMatches) emitChains(*best, lm, p.confidence);
}

bool AutoMapper::run(AutoCorrespondReport& rep) {
  // The roots correspond; the rest of their chains align below them (a tree parked under an extra
  // frame, or its placing frame removed).
  std::vector<int> ca = A_.chainSlots(A_.chainFrom(0)), cb = B_.chainSlots(B_.chainFrom(0));
  ca.erase(ca.begin());
  cb.erase(cb.begin());
  Pair top{0, 0, 1.0f};
  for (const auto& [a, b] : alignChains(A_, ca, B_, cb, st_.timeSecA, st_.timeSecB)) {
    if (artistA_.count(a) || artistB_.count(b)) break;
    link(a, b, 1.0f);
    top = {a, b, 1.0f};
  }
  queue_.push_back(top);
  for (const auto& l : artist_) queue_.push_back({A_.slotOf(l.nodeA), B_.slotOf(l.nodeB), 1.0f});
  const double total = double(A_.size());
  double done = 0.0;
  while (!queue_.empty()) {
    if (st_.cancel && st_.cancel->load(std::memory_order_relaxed)) return false;
    Pair p = queue_.front();
    queue_.pop_front();
    matchBelow(p, rep);
    if (st_.progress) st_.progress(std::min(done += 1.0, total - 1.0), total);
  }
  return true;
}

// Keeps the longest run of links (most confident first) that validates, dropping each link that
// breaks a rule; a binary search per dropped link.
std::vector<CorrespondenceLink> validPrefix(const BlobTree& a, const BlobTree& b, CorrespondenceGraph base,
                                            std::vector<CorrespondenceLink> cand, int* dropped) {
  const size_t fixed = base.links.size();
  auto valid = [&](size_t count) {
    base.links.resize(fixed);
    base.links.insert(base.links.end(), cand.begin(), cand.begin() + long(count));
    return validateCorrespondence(a, b, base).ok();
  };
  size_t good = 0;
  while (good < cand.size()) {
    if (valid(cand.size())) return cand;
    size_t lo = good, hi = cand.size();  // valid(lo), !valid(hi)
    while (hi - lo > 1) {
      size_t mid = (lo + hi) / 2;
      (valid(mid) ? lo : hi) = mid;
    }
    cand.erase(cand.begin() + long(lo));  // the link that breaks a rule
    ++*dropped;
    good = lo;
  }
  return cand;
}

}  // namespace

Result<CorrespondenceGraph> autoCorrespond(const BlobTree& a, const BlobTree& b, const CorrespondenceGraph& existing,
                                           const AutoCorrespondSettings& st, AutoCorrespondReport* report) {
  if (Status s = validateCorrespondence(a, b, existing); !s) return Error{"the existing graph is not valid: " + s.error()};
  AutoCorrespondReport rep;
  CorrespondenceGraph out;
  for (const auto& l : existing.links) {
    if (l.artist) {
      out.links.push_back(l);
      ++rep.artistKept;
    } else {
      ++rep.automaticDropped;
    }
  }
  AutoMapper mapper(a, b, st, out.links);
  auto cancelled = [&] { return st.cancel && st.cancel->load(std::memory_order_relaxed); };
  if (!mapper.run(rep) || cancelled()) return Error{"auto-map cancelled"};
  std::vector<CorrespondenceLink> applied, suggested;
  for (const auto& l : mapper.links) (l.confidence >= st.suggestBelow ? applied : suggested).push_back(l);
  std::stable_sort(applied.begin(), applied.end(),
                   [](const auto& x, const auto& y) { return x.confidence > y.confidence; });
  applied = validPrefix(a, b, out, std::move(applied), &rep.dropped);
  double confidenceSum = 0.0;
  for (const auto& l : applied) confidenceSum += l.confidence;
  rep.proposed = int(applied.size());
  rep.suggested = int(suggested.size());
  rep.meanConfidence = rep.proposed > 0 ? confidenceSum / rep.proposed : 0.0;
  out.links.insert(out.links.end(), applied.begin(), applied.end());
  out.suggestions = std::move(suggested);
  if (report) *report = rep;
  if (st.progress) st.progress(double(a.root.subtreeSize()), double(a.root.subtreeSize()));
  return out;
}

}  // namespace animorph
