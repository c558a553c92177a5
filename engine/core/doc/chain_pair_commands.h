#pragma once
// Undoable edits of a morph's artist chain pairs (MorphSetup::chainPairs,
// standin_morph/chain_pair.h): pairing a source chain with a target chain or leaving
// it unmatched, resetting one chain or all of them to the automatic matching.
// Each is one undo step over the whole list.
#include <memory>
#include <string>
#include <vector>

#include "core/doc/command.h"

namespace animorph {

// Pure edits (the commands and animorph-cli correspond run these on copies).
// Sets pair.source's pairing, replacing an earlier one for the same source; a
// pair of another source with the same target is removed (the new pair takes
// the target).
void setChainPair(std::vector<ChainPair>& pairs, ChainPair pair);
// Removes source's pairing; false when it has none.
bool resetChainPair(std::vector<ChainPair>& pairs, const std::string& source);
// The pairs of the morph with source and target swapped: each pair reversed;
// a chain left unmatched names the new target's chain, so its entry goes.
std::vector<ChainPair> swappedChainPairs(const std::vector<ChainPair>& pairs);

// "Pair chain SRC with TGT" / "Leave chain SRC unmatched". Null when the pair is already set.
std::unique_ptr<Command> setChainPairCommand(const Project& p, ChainPair pair);
// "Reset chain SRC to automatic". Null when source has no pairing.
std::unique_ptr<Command> resetChainPairCommand(const Project& p, const std::string& source);
// "Reset all chains to automatic". Null when there is no pairing.
std::unique_ptr<Command> resetAllChainPairsCommand(const Project& p);

}  // namespace animorph
