#pragma once
// Validation of a BlobTree built in code or read from JSON. Every error names
// the node id (and type and name), the parameter or child count, and the reason.
#include <string>
#include <vector>

#include "core/blobtree/blob_tree.h"
#include "core/util/result.h"

namespace animorph {

// "node 7 'thigh' (convSegment)": how errors refer to a node.
std::string describeNode(const BlobNode& n);

// Checks: parameters present with the right kind, finite key values (no NaN /
// infinity), radius-like values >= 0, q >= 1, scales non-zero, child counts,
// unique ids, threshold > 0. Returns the first error found, or success.
Status validateBlobTree(const BlobTree& tree);

// The same checks for one subtree; ids seen so far are tracked in `ids`.
Status validateBlobNode(const BlobNode& node, std::vector<int>& ids);

}  // namespace animorph
