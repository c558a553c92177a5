#pragma once
// An index over one BlobTree for the correspondence code: node by id, parent,
// depth and pre-order interval, so "is x inside the sub-tree of y" is O(1).
// It points into the tree: rebuild it after the tree changes.
#include <unordered_map>
#include <vector>

#include "core/blobtree/blob_tree.h"

namespace animorph {

class TreeIndex {
 public:
  explicit TreeIndex(const BlobTree& tree);

  bool contains(int id) const { return slot_.count(id) != 0; }
  // The node with this id (must exist).
  const BlobNode& node(int id) const { return *entries_[slot(id)].node; }
  // Parent id, or -1 for the root.
  int parent(int id) const { return entries_[slot(id)].parent; }
  int depth(int id) const { return entries_[slot(id)].depth; }
  int rootId() const { return entries_.front().node->id; }
  // True when `id` lies strictly inside the sub-tree of `ancestor`.
  bool strictlyBelow(int id, int ancestor) const;
  // Every id, in pre-order.
  std::vector<int> ids() const;

 private:
  struct Entry {
    const BlobNode* node;
    int parent;
    int depth;
    int enter;  // pre-order number
    int leave;  // largest pre-order number in the sub-tree
  };
  size_t slot(int id) const { return slot_.at(id); }
  int visit(const BlobNode& n, int parent, int depth);
  std::vector<Entry> entries_;
  std::unordered_map<int, size_t> slot_;
};

// "'thigh' (id 7)": how correspondence messages name a node.
std::string nameOfNode(const BlobNode& n);

}  // namespace animorph
