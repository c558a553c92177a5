#include "core/standin_morph/chain_matching.h"

namespace animorph {

int matchedAnchor(const SkeletonChains& own, const std::vector<int>& match, int chain) {
  int anchor = chain;
  while (anchor >= 0 && match[size_t(anchor)] < 0) anchor = own.chains[size_t(anchor)].parent;
  return anchor;
}

std::string chainPartnerText(const SkeletonChains& own, const SkeletonChains& other, const std::vector<int>& match,
                             int chain, const char* verb) {
  if (match[size_t(chain)] >= 0) return "<-> " + other.chains[size_t(match[size_t(chain)])].name;
  const int anchor = matchedAnchor(own, match, chain);
  if (anchor < 0) return std::string(verb) + " the root";
  return std::string(verb) + " " + other.chains[size_t(match[size_t(anchor)])].name;
}

}  // namespace animorph
