#include "core/animorphosis/auto_correspond.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>
#include <unordered_set>

#include "core/animorphosis/assignment.h"
#include "core/animorphosis/tree_geometry.h"
#include "core/animorphosis/tree_index.h"
#include "core/animorphosis/validate_correspondence.h"

namespace animorph {

namespace {

enum class Family { Primitive, Operator, Map, Other };

Family familyOf(NodeType t) {
  if (t <= NodeType::Capsule || t == NodeType::CoonsPatch) return Family::Primitive;
  if (t == NodeType::Blend || t == NodeType::Union || t == NodeType::HyperBlend) return Family::Operator;
  if (t >= NodeType::Frame && t <= NodeType::Bend) return Family::Map;
  return Family::Other;
}

double kindCost(NodeType x, NodeType y) {
  if (x == y) return 0.0;
  Family f = familyOf(x);
  return f == familyOf(y) && f != Family::Other ? 0.5 : 1.0;
}

// Positions and sizes in a tree's normalised box (largest side 1, lowest corner 0).
struct Shape {
  glm::vec3 centre;
  glm::vec3 size;
  double nodes;
  double kids;
};

struct Side {
  const BlobTree& tree;
  TreeIndex index;
  std::unordered_map<int, Shape> shapes;

  Side(const BlobTree& t, double timeSec) : tree(t), index(t) {
    auto ext = worldExtents(t, timeSec);
    const NodeExtent& all = ext.at(t.root.id);
    glm::vec3 lo = all.count > 0 ? all.lo : glm::vec3(0.0f);
    glm::vec3 side = all.size();
    float scale = std::max({side.x, side.y, side.z, 1e-6f});
    for (int id : index.ids()) {
      const NodeExtent& e = ext.at(id);
      const BlobNode& n = index.node(id);
      shapes[id] = {(e.count > 0 ? e.centroid() - lo : 0.5f * side) / scale, e.size() / scale,
                    double(n.subtreeSize()), double(n.children.size())};
    }
  }
};

double relativeDifference(double x, double y) { return std::abs(x - y) / std::max({x, y, 1.0}); }

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
  const std::vector<CorrespondenceLink> artist = out.links;
  Side sa(a, st.timeSecA), sb(b, st.timeSecB);
  std::unordered_set<int> artistA, artistB;
  for (const auto& l : artist) {
    artistA.insert(l.nodeA);
    artistB.insert(l.nodeB);
  }
  // An automatic link x -> y must agree with every artist link on what lies inside what.
  auto agrees = [&](int x, int y) {
    for (const auto& l : artist) {
      if (sa.index.strictlyBelow(l.nodeA, x) != sb.index.strictlyBelow(l.nodeB, y)) return false;
      if (sa.index.strictlyBelow(x, l.nodeA) != sb.index.strictlyBelow(y, l.nodeB)) return false;
    }
    return true;
  };
  // Positions are compared as offsets from the already matched parents, so two creatures whose parts
  // sit alike around their bodies match even when their boxes differ.
  auto cost = [&](const BlobNode& x, const BlobNode& y, const Shape& px, const Shape& py) {
    const Shape& p = sa.shapes.at(x.id);
    const Shape& q = sb.shapes.at(y.id);
    return st.kindWeight * kindCost(x.type, y.type) +
           st.positionWeight * glm::distance(p.centre - px.centre, q.centre - py.centre) +
           st.sizeWeight * glm::distance(p.size, q.size) +
           st.hierarchyWeight * (relativeDifference(p.nodes, q.nodes) + relativeDifference(p.kids, q.kids));
  };

  std::deque<std::pair<const BlobNode*, const BlobNode*>> queue;
  queue.push_back({&a.root, &b.root});
  for (const auto& l : artist) queue.push_back({&sa.index.node(l.nodeA), &sb.index.node(l.nodeB)});
  double confidenceSum = 0.0;
  while (!queue.empty()) {
    auto [pa, pb] = queue.front();
    queue.pop_front();
    std::vector<const BlobNode*> xs, ys;
    for (const BlobNode& c : pa->children)
      if (!artistA.count(c.id)) xs.push_back(&c);
    for (const BlobNode& c : pb->children)
      if (!artistB.count(c.id)) ys.push_back(&c);
    if (xs.empty() || ys.empty()) continue;
    int rows = int(xs.size()), cols = int(ys.size());
    std::vector<double> m(size_t(rows) * size_t(cols));
    // Costs are capped just above maxCost: a pair that will not be linked anyway must not pull the
    // assignment of the others.
    const double cap = st.maxCost * 1.000001;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        m[size_t(r) * size_t(cols) + size_t(c)] =
            std::min(cap, cost(*xs[size_t(r)], *ys[size_t(c)], sa.shapes.at(pa->id), sb.shapes.at(pb->id)));
    std::vector<int> match;
    if (std::max(rows, cols) <= st.hungarianLimit) {
      match = minCostAssignment(m, rows, cols);
    } else {
      // Greedy, cheapest pair first: with distinct positions the nearest pairs are the right ones.
      std::vector<size_t> order(m.size());
      std::iota(order.begin(), order.end(), size_t(0));
      std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return m[i] < m[j]; });
      match.assign(size_t(rows), -1);
      std::vector<char> taken(size_t(cols), 0);
      for (size_t k : order) {
        int r = int(k / size_t(cols)), c = int(k % size_t(cols));
        if (match[size_t(r)] < 0 && !taken[size_t(c)]) match[size_t(r)] = c, taken[size_t(c)] = 1;
      }
    }
    for (int r = 0; r < rows; ++r) {
      int c = match[size_t(r)];
      if (c < 0) continue;
      double k = m[size_t(r) * size_t(cols) + size_t(c)];
      const BlobNode* x = xs[size_t(r)];
      const BlobNode* y = ys[size_t(c)];
      if (k > st.maxCost || !agrees(x->id, y->id)) continue;
      CorrespondenceLink l;
      l.nodeA = x->id;
      l.nodeB = y->id;
      l.artist = false;
      l.confidence = float(std::clamp(1.0 - k / st.maxCost, 0.0, 1.0));
      confidenceSum += l.confidence;
      out.links.push_back(l);
      ++rep.proposed;
      queue.push_back({x, y});
    }
  }
  rep.meanConfidence = rep.proposed > 0 ? confidenceSum / rep.proposed : 0.0;
  if (report) *report = rep;
  return out;
}

}  // namespace animorph
