#pragma once
// animorph-cli correspond's chain pair edits: --pair SRC=TGT (pair source chain
// SRC with target chain TGT), --unpair SRC (leave SRC unmatched), --auto SRC
// (SRC back to the automatic matching), --auto-all. Chains are named by their
// first joint (standin_morph/chain_pair.h).
#include <string>
#include <vector>

#include "core/standin_morph/skeleton_correspondence.h"

namespace animorph::cli {

struct ChainPairEdit {
  enum class Kind { Pair, Unpair, Automatic, AllAutomatic } kind;
  std::string source, target;
};

// Reads the edit option args[i] (advancing i past its value) into edits; false
// when args[i] is none of them. error: a missing or malformed value.
bool readChainPairOption(const std::vector<std::string>& args, size_t& i, std::vector<ChainPairEdit>& edits,
                         std::string& error);

// Applies edits in order to pairs, each name checked against the chains of c
// (the rigs' chains: source names against c.source, targets against c.target).
// Error: "--pair Foo=Hub: no source chain starts at joint 'Foo' (chains: ...)".
bool applyChainPairEdits(const std::vector<ChainPairEdit>& edits, const SkeletonCorrespondence& c,
                         std::vector<ChainPair>& pairs, std::string& error);

}  // namespace animorph::cli
