#include "core/animorphosis/tree_index.h"

#include <string>

namespace animorph {

TreeIndex::TreeIndex(const BlobTree& tree) { visit(tree.root, -1, 0); }

int TreeIndex::visit(const BlobNode& n, int parent, int depth) {
  size_t me = entries_.size();
  int enter = int(me);
  entries_.push_back({&n, parent, depth, enter, enter});
  slot_[n.id] = me;
  int last = enter;
  for (const BlobNode& c : n.children) last = visit(c, n.id, depth + 1);
  entries_[me].leave = last;
  return last;
}

bool TreeIndex::strictlyBelow(int id, int ancestor) const {
  const Entry& e = entries_[slot(id)];
  const Entry& a = entries_[slot(ancestor)];
  return e.enter > a.enter && e.enter <= a.leave;
}

std::vector<int> TreeIndex::ids() const {
  std::vector<int> r;
  r.reserve(entries_.size());
  for (const Entry& e : entries_) r.push_back(e.node->id);
  return r;
}

std::string nameOfNode(const BlobNode& n) {
  std::string s = n.name.empty() ? std::string(nodeTypeInfo(n.type).name) : "'" + n.name + "'";
  return s + " (id " + std::to_string(n.id) + ")";
}

}  // namespace animorph
