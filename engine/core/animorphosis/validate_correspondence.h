#pragma once
// Validation of a correspondence graph against its source tree A and target
// tree B. A refusal names both nodes of the refused link (by name and id),
// the link it conflicts with, and the rule broken.
#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"
#include "core/util/result.h"

namespace animorph {

// Rules, in the order checked:
//  * every link's nodes exist (A's id in A, B's in B), confidence in [0, 1],
//    s override a valid s curve (checkSCurve), no link given twice;
//  * the roots correspond to each other only (a root links to the other root or to nothing);
//  * hierarchy: for two links a1 -> b1 and a2 -> b2, if a2 lies inside a1's
//    sub-tree then b2 lies inside the sub-tree of b1 or of another partner of
//    a1 (links below a link stay inside the linked sub-trees), and the same
//    with A and B swapped;
//  * no crossing: links from two separate sub-trees of A do not go to a node
//    and its descendant in B, and a node's several partners are in separate
//    sub-trees (so splitting it gives each copy its own partner).
Status validateCorrespondence(const BlobTree& a, const BlobTree& b, const CorrespondenceGraph& graph);

}  // namespace animorph
