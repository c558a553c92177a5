#pragma once
// The generic tree C of an animorphosis (docs/animorphosis.md): the source A
// and the target B rewritten with one common structure, every node of C a
// pair (A' node, B' node). Built from a valid correspondence graph by
//  * splitting: a node whose sub-tree links to k separate sub-trees of the
//    other side is split into k copies, each keeping the links to one of them;
//    a primitive under a sum (blend, frame, warp) becomes k copies of
//    intensity I/k, under a union or intersection k full copies; an inner
//    node keeps one copy per partner, unlinked material shared the same way,
//    so A' has the field of A and B' that of B;
//  * null partners: an unlinked sub-tree is paired with a copy of itself of
//    zero intensity (warps: the identity warp) collapsed to one anchor: the
//    centroid of the partner of its nearest linked sibling, else of the
//    partner's children, so a part grows out of its linked neighbour;
//  * identities: a node one side has and the other lacks on the path to a link
//    (an extra frame, warp or operator) is paired with the identity of its
//    kind (frame T = 0, R = 1, S = 1; twist and bend angle 0; taper scales 1;
//    a blend, union, intersection or hyper-blend of one child);
//  * bridging: blend, union and hyper-blend pair with each other (C evaluates
//    a hyper-blend whose q goes from one to the other); primitives of other
//    kinds linked together become two pairs, one shrinking to zero intensity,
//    one growing from it, at their own places.
#include <vector>

#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"
#include "core/util/result.h"

namespace animorph {

enum class MorphSide { A, B };

struct GenericNode {
  BlobNode a;          // A' node: type and parameters (its children are below, in `children`)
  BlobNode b;          // B' node: the same type, or a blend / union / hyper-blend where bridged
  int sCurve = -1;     // index in GenericTree::sCurves of the s(u) driving this node; -1: the global one
  int sourceA = -1;    // id of the node of A this comes from; -1: made here (null partner, identity)
  int sourceB = -1;
  std::vector<GenericNode> children;
};

struct GenericTree {
  FloatTrack thresholdA{1.0f};
  FloatTrack thresholdB{1.0f};
  GenericNode root;
  std::vector<FloatTrack> sCurves;  // the links' s overrides in use
  int splitCopies = 0;              // copies added by splitting (a node split in k adds k - 1)
  int nullPartners = 0;             // sub-trees given a null partner
  size_t size() const;              // number of nodes of C
};

struct GenericOptions {
  double anchorTimeSecA = 0.0;  // time of A (clip time) at which null-partner anchors are measured
  double anchorTimeSecB = 0.0;
};

// Builds C. The graph must pass validateCorrespondence (this checks it again);
// also refused, with both nodes named: a split that would change the field
// (e.g. a union's children shared out under a blend), an unlinked child of an
// intersection or of a fixed-order operator whose partner differs, an
// unlinked sub-tree holding an R-function or bounded blend (its zero copy is
// not empty), a bridged hyper-blend of more than 64 children.
Result<GenericTree> buildGenericTree(const BlobTree& a, const BlobTree& b, const CorrespondenceGraph& graph,
                                     const GenericOptions& options = {});

// A' or B' as a plain BlobTree with ids 1..n in pre-order: the field of A (or B) at every time.
BlobTree genericSide(const GenericTree& c, MorphSide side);

}  // namespace animorph
