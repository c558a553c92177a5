#pragma once
// Seeded variants of a BlobTree that an artist could make, each with the
// identity it keeps: which nodes of the variant every node of the original is
// (docs/animorphosis.md, "Automatic correspondence", defines the identity).
// The automatic correspondence is scored against that identity.
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"

namespace animorph::test {

enum class Perturbation {
  Wrap,         // a sub-tree wrapped in an identity frame, twist or one-child blend
  Regroup,      // two or more children of a group moved into a new sub-group of the same kind
  Split,        // a segment (segment, cone, capsule, convolution segment, cylinder) cut into 2 or 3 along its axis
  SplineChain,  // a spline of nodes replaced by the chain of its copies, or a chain of points by a spline
  DropAdd,      // a primitive dropped, or a small primitive added next to another (alternately)
  Rename,       // every node renamed (ids are renumbered and groups shuffled in every variant)
  Place,        // the whole tree put under a moved, rotated and uniformly scaled frame
  Retime,       // every key time scaled by a factor (the animation slower or faster)
};

std::vector<Perturbation> allPerturbations();
const char* perturbationName(Perturbation p);

struct PerturbedTree {
  BlobTree tree;
  // For every node of the original but its root: the nodes of `tree` it is (two or three for a
  // split segment; none for a dropped part, a spline or chain member that has no node of its
  // own in the variant). Nodes of `tree` that are no node's identity (wrappers, new groups, added
  // parts) are in no list.
  std::unordered_map<int, std::vector<int>> identity;
  int edits = 0;  // edits made (a kind with nothing to edit in this tree makes none)
};

// `edits` edits, each of a kind drawn from `kinds`; then every id is renumbered and the children
// of every commuting node shuffled.
PerturbedTree perturbTree(const BlobTree& original, const std::vector<Perturbation>& kinds, int edits,
                          std::mt19937& rng);

struct RecoveryScore {
  int counted = 0;        // nodes of the original scored (all but the root)
  double recovered = 0.0; // share of the identity recovered: per node, the share of its identity nodes it
                          // is linked to (1 for a node with none that has no link), averaged
  int links = 0;          // links applied
  int wrongLinks = 0;     // applied links to a node outside the A node's identity
  int suggestions = 0;    // suggestions (not applied)
  int rightSuggestions = 0;
  double wrong() const { return links > 0 ? double(wrongLinks) / links : 0.0; }
};

RecoveryScore scoreRecovery(const BlobTree& original, const CorrespondenceGraph& g,
                            const std::unordered_map<int, std::vector<int>>& identity);

}  // namespace animorph::test
