#pragma once
// Automatic correspondence between two stand-ins by skeleton chains (docs/morph.md,
// "Skeleton correspondence"). Each stand-in's segments hang under joints of
// its character's rig; the joints that carry segments form a tree (a joint's
// parent is its nearest ancestor with segments). The tree is split at branch
// joints into chains (root to branch, branch to branch, branch to tip). Each
// chain is described, in the rest pose and relative to the rig's root joint,
// by its side (sign of x), its direction from the root, its length as a share
// of the rig's and its sub-tree's share of the segments; chains are matched
// by a minimum-cost assignment over these features, the main root chains with
// each other. Artist pairs (standin_morph/chain_pair.h) are fixed first: the
// assignment fills in the remaining chains only, and the root rule holds only
// while neither main root chain is in an artist pair. Along a chain, every segment covers an interval of normalised
// arc length; a segment of one side maps onto the segment of the matched
// chain that covers its interval's middle (its ends clamped to that
// segment). A segment of an unmatched chain maps onto the point where its
// chain branches off its nearest matched ancestor, with its own radius: it shrinks
// into (or grows out of) its matched neighbour.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/standin_morph/chain_pair.h"
#include "core/rig/character.h"
#include "core/standin/standin.h"

namespace animorph {

struct SkeletonChain {
  std::vector<int> nodes;       // character nodes, from the chain's start to its tip
  std::vector<int> segments;    // stand-in segments on those nodes, in chain order
  std::vector<float> from, to;  // per segment: its interval of normalised arc length in [0, 1]
  int parent = -1;              // the chain it branches from (-1: a root chain)
  float attach = 1.0f;          // where it branches off the parent chain (normalised arc length)
  // Matching features (rest pose, the character's own frame):
  int side = 0;                 // -1, 0, +1: x of the chain's centroid against the root joint's
  glm::vec3 direction{0.0f};    // unit direction from the root joint to the chain's centroid (0: at the root)
  float length = 0.0f;          // chain length / sum of every chain's length
  float subtree = 0.0f;         // segments of the chain and the chains below it / all segments
  std::string name;             // its first node's name
};

// The chains of one stand-in.
struct SkeletonChains {
  std::vector<SkeletonChain> chains;
  std::vector<int> chainOfSegment;  // per stand-in segment; -1: its node is not in the rig
  int mainRoot = -1;                // the root chain with the largest sub-tree
};

// Chains of stand-in s on character c (rest pose). Segments whose node is out
// of range belong to no chain.
SkeletonChains skeletonChains(const Character& c, const Standin& s);

// Feature distance between two chains (0: same side, direction, length and sub-tree share).
float chainMatchCost(const SkeletonChain& a, const SkeletonChain& b);

// Chains whose best assignment costs more than this stay unmatched.
inline constexpr float kMaxChainMatchCost = 1.5f;

struct SkeletonCorrespondence {
  SkeletonChains source, target;
  std::vector<int> sourceMatch;  // per source chain: its target chain, -1: unmatched
  std::vector<int> targetMatch;  // per target chain: its source chain, -1: unmatched
  std::vector<float> cost;       // per source chain: chainMatchCost of its match (0 when unmatched)
  // Per source chain: 1 when an artist pair sets its match (sourceMatch[i] then
  // is the pair's target, -1 for "unmatched").
  std::vector<char> pinned;
  // Per source chain: its match by the automatic rule with its own artist pair
  // left out (the others kept); equals sourceMatch for a chain without one.
  std::vector<int> automatic;
  // Artist pairs that could not be applied, one line each, e.g.
  // "chain_pairs[1].target: no target chain starts at joint 'Hub2': pair ignored".
  std::vector<std::string> warnings;
};

// The chain whose first joint is named name, or -1.
int chainNamed(const SkeletonChains& chains, const std::string& name);

// pairs: the artist's, applied first (a pair naming a chain that does not
// exist, a source named twice or a target already taken is skipped with a
// warning); the automatic assignment matches the chains left over.
SkeletonCorrespondence correspondSkeletons(SkeletonChains source, SkeletonChains target,
                                           const std::vector<ChainPair>& pairs = {});

// Where segment `segment` of one side goes on the other side, posed: a segment
// of the other side's posed stand-in (or a point of it, for an unmatched chain),
// with the radius and weight scale it takes there.
struct SegmentImage {
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.0f;
  float weightScale = 0.0f;
};

// from / onto: the chains of the segment's side and of the other side;
// match: from's chain -> onto's chain (sourceMatch or targetMatch); ontoPosed:
// the other side's posed stand-in (one entry per segment of its stand-in).
SegmentImage segmentImage(const SkeletonChains& from, int segment, const SkeletonChains& onto,
                          const std::vector<int>& match, const std::vector<PosedSegment>& ontoPosed,
                          float ownRadius);

}  // namespace animorph
