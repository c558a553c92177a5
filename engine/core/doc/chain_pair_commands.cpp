#include "core/doc/chain_pair_commands.h"

#include <algorithm>

namespace animorph {
namespace {

std::unique_ptr<Command> setPairs(const Project& p, std::vector<ChainPair> after, std::string label) {
  if (after == p.morph.chainPairs) return nullptr;
  return std::make_unique<SetValueCommand<std::vector<ChainPair>>>(
      std::move(label), [](Project& proj) { return &proj.morph.chainPairs; }, p.morph.chainPairs, std::move(after));
}

}  // namespace

void setChainPair(std::vector<ChainPair>& pairs, ChainPair pair) {
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](const ChainPair& q) {
                               return q.source != pair.source && pair.target && q.target == pair.target;
                             }),
              pairs.end());
  auto it = std::find_if(pairs.begin(), pairs.end(), [&](const ChainPair& q) { return q.source == pair.source; });
  if (it != pairs.end()) *it = std::move(pair);
  else pairs.push_back(std::move(pair));
}

bool resetChainPair(std::vector<ChainPair>& pairs, const std::string& source) {
  const size_t before = pairs.size();
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const ChainPair& q) { return q.source == source; }),
              pairs.end());
  return pairs.size() != before;
}

std::vector<ChainPair> swappedChainPairs(const std::vector<ChainPair>& pairs) {
  std::vector<ChainPair> out;
  for (const ChainPair& p : pairs)
    if (p.target) out.push_back({*p.target, p.source});
  return out;
}

std::unique_ptr<Command> setChainPairCommand(const Project& p, ChainPair pair) {
  const std::string label = pair.target ? "Pair chain " + pair.source + " with " + *pair.target
                                        : "Leave chain " + pair.source + " unmatched";
  std::vector<ChainPair> after = p.morph.chainPairs;
  setChainPair(after, std::move(pair));
  return setPairs(p, std::move(after), label);
}

std::unique_ptr<Command> resetChainPairCommand(const Project& p, const std::string& source) {
  std::vector<ChainPair> after = p.morph.chainPairs;
  if (!resetChainPair(after, source)) return nullptr;
  return setPairs(p, std::move(after), "Reset chain " + source + " to automatic");
}

std::unique_ptr<Command> resetAllChainPairsCommand(const Project& p) {
  return setPairs(p, {}, "Reset all chains to automatic");
}

}  // namespace animorph
