#pragma once
// Automatic correspondence: proposes links between two BlobTrees level by
// level from the roots. For each pair of corresponding nodes, their children
// are matched by a minimum-cost assignment over a cost matrix of node kind,
// position (as an offset from the matched parent) and size in each tree's
// normalised bounding box, and place in the hierarchy (sub-tree size, child
// count); matched pairs with a cost below
// maxCost become automatic links whose confidence falls with the cost, and
// their children are matched in turn. Artist links are never touched: their
// nodes are not matched again, and no automatic link may contradict one.
#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"
#include "core/util/result.h"

namespace animorph {

struct AutoCorrespondSettings {
  double timeSecA = 0.0;         // clip time of A whose pose is compared
  double timeSecB = 0.0;         // clip time of B
  double kindWeight = 1.0;       // cost of different kinds (0.5 of it within primitives, maps, or bridged operators)
  double positionWeight = 3.0;   // cost per unit of distance between the centroids' offsets from their parents
  double sizeWeight = 1.0;       // cost per unit of difference of the normalised box sizes
  double hierarchyWeight = 0.5;  // cost of relative sub-tree size and child count differences
  double maxCost = 1.5;          // pairs costing more stay unlinked (null partners)
  int hungarianLimit = 300;      // wider levels use a greedy cheapest-pair-first assignment
};

struct AutoCorrespondReport {
  int proposed = 0;              // automatic links made
  int artistKept = 0;            // artist links carried over unchanged
  int automaticDropped = 0;      // automatic links of the input graph replaced
  double meanConfidence = 0.0;   // over the proposed links
};

// `existing` must be valid for a and b (its artist links are kept as they are,
// its automatic links are replaced). Returns a graph valid for a and b.
Result<CorrespondenceGraph> autoCorrespond(const BlobTree& a, const BlobTree& b, const CorrespondenceGraph& existing,
                                           const AutoCorrespondSettings& settings = {},
                                           AutoCorrespondReport* report = nullptr);

}  // namespace animorph
