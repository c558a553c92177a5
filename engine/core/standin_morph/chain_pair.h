#pragma once
// An artist's pairing of one source chain of a skeleton-correspondence morph
// (docs/morph.md, "Re-pairing chains by hand"), saved in the morph's
// "chain_pairs". Chains are named by their first joint's name, which stays the
// same when a rig is imported again. An artist pair is fixed before the
// automatic assignment, which fills in the remaining chains without touching it
// (standin_morph/skeleton_correspondence.h: correspondSkeletons).
#include <optional>
#include <string>

namespace animorph {

struct ChainPair {
  std::string source;                 // the source chain's first joint
  std::optional<std::string> target;  // the target chain's first joint; nullopt: left unmatched
  bool operator==(const ChainPair&) const = default;
};

}  // namespace animorph
