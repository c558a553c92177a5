#pragma once
// Automatic correspondence (docs/animorphosis.md, "Automatic correspondence"):
// proposes links between two BlobTrees from the roots down. For each pair of
// corresponding nodes, their children -- each followed down its chain of
// transparent nodes (frames, warps and operators with one child), so a wrapped
// sub-tree meets its unwrapped partner -- are matched by a minimum-cost
// assignment over shape descriptors that survive regrouping and depth changes:
// the sub-tree's place relative to the matched parents and its extent, both
// sampled over the clip (in the space inside each tree's root chain, in units
// of the tree's size), its kind and its number of primitives. A child group
// (blend, union) that matches better as its parts is opened up (regrouped
// children); a primitive whose shape is that of two or three primitives of the
// other side together is split among them (one-to-many links); a part nothing
// matches stays unlinked (null partner). Every link's confidence falls with its
// cost and with how close the next candidate came; links below
// `suggestBelow` are returned as suggestions, not applied. Artist links are
// never touched: their nodes are not matched again, and no automatic link may
// contradict one.
#include <atomic>
#include <functional>

#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"
#include "core/util/result.h"

namespace animorph {

struct AutoCorrespondSettings {
  double timeSecA = 0.0;         // clip time of A where the sampling of its clip starts
  double timeSecB = 0.0;         // clip time of B
  int clipSamples = 4;           // times sampled over each clip (its length from its last key); 1: only timeSec
  double kindWeight = 1.0;       // cost of different kinds (0.5 of it within primitives, maps, or groups)
  double positionWeight = 3.0;   // cost per unit of distance between the centroids' offsets from their parents
  double sizeWeight = 1.0;       // cost per unit of difference of the extents' sizes (units: each tree's size)
  double hierarchyWeight = 0.25; // cost of the relative difference of the sub-trees' primitive counts
  double maxCost = 1.5;          // pairs costing more stay unlinked (null partners)
  double splitMaxCost = 0.3;     // a split (one part to two or three) costing more is not proposed
  double marginScale = 0.02;     // confidence: the next candidate's extra cost against (cost / 4 + this * the parent's size)
  double suggestBelow = 0.25;    // links less confident than this are suggestions, not applied
  int hungarianLimit = 300;      // wider levels use a greedy cheapest-pair-first assignment
  // Run as a background job (the editor's Auto-map): progress(done, total) is called on the calling
  // thread after each matched level (total: the source tree's nodes, an upper bound on the levels;
  // done reaches total when the graph is complete); a set cancel flag stops the matching before the
  // next level or before the validation, and autoCorrespond returns an error saying it was cancelled.
  // Null / empty: no progress, no cancel.
  const std::atomic<bool>* cancel = nullptr;
  std::function<void(double done, double total)> progress;
};

struct AutoCorrespondReport {
  int proposed = 0;              // automatic links made (applied)
  int suggested = 0;             // links proposed below the confidence threshold (graph.suggestions)
  int splits = 0;                // nodes linked to two or three parts of the other side
  int regrouped = 0;             // groups opened up to match their parts
  int artistKept = 0;            // artist links carried over unchanged
  int automaticDropped = 0;      // automatic links of the input graph replaced
  int dropped = 0;               // proposals dropped because they broke a rule of validateCorrespondence
  double meanConfidence = 0.0;   // over the proposed links
};

// `existing` must be valid for a and b (its artist links are kept as they are,
// its automatic links and its suggestions are replaced). Returns a graph valid
// for a and b, with the links below the threshold in `suggestions`.
Result<CorrespondenceGraph> autoCorrespond(const BlobTree& a, const BlobTree& b, const CorrespondenceGraph& existing,
                                           const AutoCorrespondSettings& settings = {},
                                           AutoCorrespondReport* report = nullptr);

}  // namespace animorph
