#pragma once
// One tree as the automatic correspondence sees it (auto_correspond.h): its
// nodes in pre-order with parents and children, the extent of every sub-tree
// at a few times spread over its clip (in the space inside its root chain, so
// placing the whole tree under a moved, rotated or scaled frame changes
// nothing), the tree's size, and its transparent chains (frames, warps and
// one-child operators, which matching passes through).
#include <unordered_map>
#include <vector>

#include "core/animorphosis/tree_geometry.h"
#include "core/blobtree/blob_tree.h"

namespace animorph {

// A path of transparent nodes (isTransparentLink) from `top` down to the first
// node that is not one, `bottom` (top == bottom for an ordinary child). Slots.
struct ChainItem {
  int top = -1;
  int bottom = -1;
};

class MatchSide {
 public:
  // Samples the extents at `samples` times timeSec + k / samples * (the clip's
  // length, animationEndSec), k = 0 .. samples - 1 (one time for a still tree).
  MatchSide(const BlobTree& tree, double timeSec, int samples);

  int size() const { return int(nodes_.size()); }
  int samples() const { return samples_; }
  const BlobNode& node(int slot) const { return *nodes_[size_t(slot)]; }
  int slotOf(int id) const { return slotOf_.at(id); }
  bool has(int id) const { return slotOf_.count(id) != 0; }
  int parent(int slot) const { return parent_[size_t(slot)]; }
  const std::vector<int>& children(int slot) const { return children_[size_t(slot)]; }
  // True when slot lies strictly inside the sub-tree of ancestor.
  bool below(int slot, int ancestor) const { return slot > ancestor && slot <= last_[size_t(ancestor)]; }
  // The extents of slot's sub-tree at each sample (samples() of them, contiguous).
  const NodeExtent* extents(int slot) const { return &extents_[size_t(slot) * size_t(samples_)]; }
  // Primitives (leaves and meta-primitives) in slot's sub-tree.
  float primitives(int slot) const { return primitives_[size_t(slot)]; }
  // Diagonal of the whole tree's box at the first sample (> 0): the unit of positions and sizes.
  float scale() const { return scale_; }

  // The chain starting at slot (slot itself when it is not transparent).
  ChainItem chainFrom(int slot) const;
  // Every slot of a chain, top to bottom.
  std::vector<int> chainSlots(const ChainItem& c) const;
  // The children of slot, each followed down its chain.
  std::vector<ChainItem> items(int slot) const;

 private:
  int visit(const BlobNode& n, int parent);
  std::vector<const BlobNode*> nodes_;
  std::vector<int> parent_, last_;
  std::vector<std::vector<int>> children_;
  std::vector<float> primitives_;
  std::unordered_map<int, int> slotOf_;
  std::vector<NodeExtent> extents_;
  int samples_ = 1;
  float scale_ = 1.0f;
};

}  // namespace animorph
