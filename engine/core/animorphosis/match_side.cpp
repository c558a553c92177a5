#include "core/animorphosis/match_side.h"

#include <algorithm>
#include <cmath>

#include "core/blobtree/tree_edit.h"

namespace animorph {

MatchSide::MatchSide(const BlobTree& tree, double timeSec, int samples) {
  visit(tree.root, -1);
  const double length = animationEndSec(tree);
  samples_ = length > 0.0 ? std::max(1, samples) : 1;
  extents_.resize(nodes_.size() * size_t(samples_));
  std::vector<NodeExtent> at;
  for (int k = 0; k < samples_; ++k) {
    extentsInsideRootChain(tree, timeSec + length * k / samples_, at);
    for (size_t s = 0; s < at.size(); ++s) extents_[s * size_t(samples_) + size_t(k)] = at[s];
  }
  const NodeExtent& all = extents_[0];
  scale_ = std::max(1e-6f, glm::length(all.size()));
}

int MatchSide::visit(const BlobNode& n, int parent) {
  const int me = int(nodes_.size());
  nodes_.push_back(&n);
  parent_.push_back(parent);
  last_.push_back(me);
  children_.emplace_back();
  primitives_.push_back(0.0f);
  slotOf_[n.id] = me;
  float prims = n.children.empty() || n.type == NodeType::SplineOfNodes ? 1.0f : 0.0f;
  for (const BlobNode& c : n.children) {
    const int slot = visit(c, me);
    children_[size_t(me)].push_back(slot);
    if (n.type != NodeType::SplineOfNodes) prims += primitives_[size_t(slot)];
  }
  // A spline of nodes stands for its copies (so it meets the chain of them it replaces).
  if (n.type == NodeType::SplineOfNodes)
    prims = std::max(1.0f, std::round(n.floatParam("count").evaluate(0.0))) * primitives_[size_t(me) + 1];
  primitives_[size_t(me)] = prims;
  last_[size_t(me)] = int(nodes_.size()) - 1;
  return me;
}

ChainItem MatchSide::chainFrom(int slot) const {
  int bottom = slot;
  while (isTransparentLink(node(bottom))) bottom = children_[size_t(bottom)].front();
  return {slot, bottom};
}

std::vector<int> MatchSide::chainSlots(const ChainItem& c) const {
  std::vector<int> r{c.top};
  for (int s = c.top; s != c.bottom;) r.push_back(s = children_[size_t(s)].front());
  return r;
}

std::vector<ChainItem> MatchSide::items(int slot) const {
  std::vector<ChainItem> r;
  r.reserve(children_[size_t(slot)].size());
  for (int c : children_[size_t(slot)]) r.push_back(chainFrom(c));
  return r;
}

}  // namespace animorph
