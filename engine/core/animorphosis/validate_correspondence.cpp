#include "core/animorphosis/validate_correspondence.h"

#include <cmath>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/animorphosis/tree_index.h"

namespace animorph {

namespace {

enum class Relation { Same, Above, Below, Apart };

Relation relation(const TreeIndex& ix, int x, int y) {
  if (x == y) return Relation::Same;
  if (ix.strictlyBelow(y, x)) return Relation::Above;
  if (ix.strictlyBelow(x, y)) return Relation::Below;
  return Relation::Apart;
}

struct Checker {
  const TreeIndex& ia;
  const TreeIndex& ib;
  const CorrespondenceGraph& g;
  std::unordered_map<int, std::vector<int>> byA, byB;  // link indices by node

  Checker(const TreeIndex& a, const TreeIndex& b, const CorrespondenceGraph& graph) : ia(a), ib(b), g(graph) {
    for (size_t i = 0; i < g.links.size(); ++i) {
      byA[g.links[i].nodeA].push_back(int(i));
      byB[g.links[i].nodeB].push_back(int(i));
    }
  }

  std::string linkName(const CorrespondenceLink& l) const {
    return "source " + nameOfNode(ia.node(l.nodeA)) + " -> target " + nameOfNode(ib.node(l.nodeB));
  }

  // Some partner of source node `a` contains target node `b` strictly.
  bool otherPartnerOfAContains(int a, int b) const {
    for (int i : byA.at(a))
      if (ib.strictlyBelow(b, g.links[size_t(i)].nodeB)) return true;
    return false;
  }
  bool otherPartnerOfBContains(int b, int a) const {
    for (int i : byB.at(b))
      if (ia.strictlyBelow(a, g.links[size_t(i)].nodeA)) return true;
    return false;
  }

  // Link i against every link whose node in A or in B is i's node or one of its ancestors: every
  // pair of links is met this way unless its nodes are apart on both sides, which is always allowed.
  Status link(int i) const {
    const CorrespondenceLink& l = g.links[size_t(i)];
    for (int side = 0; side < 2; ++side) {
      const TreeIndex& ix = side == 0 ? ia : ib;
      const auto& by = side == 0 ? byA : byB;
      for (int x = side == 0 ? l.nodeA : l.nodeB; x != -1; x = ix.parent(x)) {
        auto it = by.find(x);
        if (it == by.end()) continue;
        for (int j : it->second) {
          if (j == i) continue;
          Status s = j < i ? pair(g.links[size_t(j)], l) : pair(l, g.links[size_t(j)]);
          if (!s) return s;
        }
      }
    }
    return Status::success();
  }

  Status refuse(const CorrespondenceLink& bad, const CorrespondenceLink& other, const std::string& why) const {
    return Error{"link " + linkName(bad) + " is refused: with link " + linkName(other) + ", " + why};
  }

  // Link `l2` checked against `l1` (l1 comes first in the graph).
  Status pair(const CorrespondenceLink& l1, const CorrespondenceLink& l2) const {
    Relation ra = relation(ia, l1.nodeA, l2.nodeA);
    Relation rb = relation(ib, l1.nodeB, l2.nodeB);
    if (ra == rb && ra != Relation::Same) return Status::success();  // nested alike, or apart on both sides
    if (ra == Relation::Same && rb == Relation::Apart) return Status::success();  // a split of a1
    if (rb == Relation::Same && ra == Relation::Apart) return Status::success();  // a split of b1
    const std::string a1 = nameOfNode(ia.node(l1.nodeA)), a2 = nameOfNode(ia.node(l2.nodeA));
    const std::string b1 = nameOfNode(ib.node(l1.nodeB)), b2 = nameOfNode(ib.node(l2.nodeB));
    if (ra == Relation::Same)
      return refuse(l2, l1, "source " + a1 + " would link to " + b1 + " and to its " +
                                (rb == Relation::Above ? "descendant " : "ancestor ") + b2 +
                                " (the partners of one node must be in separate sub-trees)");
    if (rb == Relation::Same)
      return refuse(l2, l1, "target " + b1 + " would link to " + a1 + " and to its " +
                                (ra == Relation::Above ? "descendant " : "ancestor ") + a2 +
                                " (the partners of one node must be in separate sub-trees)");
    // Nested on one side only: allowed when another partner of the outer node holds the inner one.
    if (ra == Relation::Above && rb == Relation::Apart && otherPartnerOfAContains(l1.nodeA, l2.nodeB))
      return Status::success();
    if (ra == Relation::Below && rb == Relation::Apart && otherPartnerOfAContains(l2.nodeA, l1.nodeB))
      return Status::success();
    if (rb == Relation::Above && ra == Relation::Apart && otherPartnerOfBContains(l1.nodeB, l2.nodeA))
      return Status::success();
    if (rb == Relation::Below && ra == Relation::Apart && otherPartnerOfBContains(l2.nodeB, l1.nodeA))
      return Status::success();
    if (ra == Relation::Above || ra == Relation::Below) {
      const std::string& inner = ra == Relation::Above ? a2 : a1;
      const std::string& outer = ra == Relation::Above ? a1 : a2;
      const std::string& innerB = ra == Relation::Above ? b2 : b1;
      const std::string& outerB = ra == Relation::Above ? b1 : b2;
      return refuse(l2, l1, "source " + inner + " lies inside " + outer + " but target " + innerB +
                                " does not lie inside " + outerB +
                                " (links below a link must stay inside the linked sub-trees)");
    }
    const std::string& inner = rb == Relation::Above ? b2 : b1;
    const std::string& outer = rb == Relation::Above ? b1 : b2;
    return refuse(l2, l1, "the links cross: target " + inner + " lies inside " + outer + " but source " + a1 +
                              " and " + a2 + " are in separate sub-trees");
  }
};

}  // namespace

Status validateCorrespondence(const BlobTree& a, const BlobTree& b, const CorrespondenceGraph& graph) {
  TreeIndex ia(a), ib(b);
  std::set<std::pair<int, int>> seen;
  for (size_t i = 0; i < graph.links.size(); ++i) {
    const CorrespondenceLink& l = graph.links[i];
    std::string where = "link " + std::to_string(i);
    if (!ia.contains(l.nodeA))
      return Error{where + ": source node id " + std::to_string(l.nodeA) + " is not in the source tree"};
    if (!ib.contains(l.nodeB))
      return Error{where + ": target node id " + std::to_string(l.nodeB) + " is not in the target tree"};
    where = "link source " + nameOfNode(ia.node(l.nodeA)) + " -> target " + nameOfNode(ib.node(l.nodeB));
    if (!std::isfinite(l.confidence) || l.confidence < 0.0f || l.confidence > 1.0f)
      return Error{where + ": confidence " + std::to_string(l.confidence) + " is outside [0, 1]"};
    if (l.sOverride) {
      Status s = checkSCurve(*l.sOverride, where + ": s override");
      if (!s) return s;
    }
    if (!seen.insert({l.nodeA, l.nodeB}).second) return Error{where + ": the link is given twice"};
    bool rootA = l.nodeA == ia.rootId(), rootB = l.nodeB == ib.rootId();
    if (rootA != rootB)
      return Error{where + " is refused: a root corresponds to the other root only (the roots are always linked)"};
  }
  Checker c(ia, ib, graph);
  for (size_t i = 0; i < graph.links.size(); ++i)
    if (Status s = c.link(int(i)); !s) return s;
  return Status::success();
}

}  // namespace animorph
