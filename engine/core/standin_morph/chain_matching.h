#pragma once
// Reading a skeleton correspondence (standin_morph/skeleton_correspondence.h) chain by
// chain, for what the user is shown (animorph-cli correspond, the inspector's
// chain matching): whom a chain is paired with, or which matched chain an
// unmatched one shrinks into / grows from.
#include <string>
#include <vector>

#include "core/standin_morph/skeleton_correspondence.h"

namespace animorph {

// The nearest chain at or above `chain` (through parents) that has a partner in
// match; -1 when none has (it goes to the other side's root).
int matchedAnchor(const SkeletonChains& own, const std::vector<int>& match, int chain);

// One line per chain of own: "<-> NAME" for a paired chain, else "VERB NAME"
// (the anchor's partner; VERB "shrinks into" for the source, "grows from" for the
// target), or "VERB the root".
std::string chainPartnerText(const SkeletonChains& own, const SkeletonChains& other, const std::vector<int>& match,
                             int chain, const char* verb);

}  // namespace animorph
