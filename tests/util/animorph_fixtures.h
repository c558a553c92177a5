#pragma once
// Two small animated creatures for the animorphosis tests: a walker (body
// frame with belly and chest, two legs under frames, a blended tail, a head)
// and a flyer (body, two flapping wings under frames, a legs frame holding
// both legs, a union tail of three beads), and a graph between them that
// exercises every rule: an inner node and a primitive split in two, a
// partner inside an unlinked frame, a blend bridged to a union, unlinked parts
// on both sides, and an s override.
#include <random>
#include <unordered_map>

#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"
#include "core/project/project.h"

namespace animorph::test {

BlobTree walkerTree();
BlobTree flyerTree();
CorrespondenceGraph walkerToFlyerGraph();
// A project named `name` with the walker and the flyer as BlobTree actors and the walker -> flyer
// animorphosis from 1 s to 3 s (automatic correspondence), timeline frames first..last.
Project walkerToFlyerProject(const std::string& name, int first = 0, int last = 96);

// A copy of `tree` moved by `offset`, scaled by `scale` about the origin
// (every skeleton point, top-level frame translation and radius transformed),
// every skeleton point then jittered by up to `jitter` (in the copy's units)
// in each axis, the children of every commuting operator shuffled, and every
// id replaced by idMap[old] (a random permutation of fresh ids).
BlobTree perturbedCopy(const BlobTree& tree, glm::vec3 offset, float scale, std::mt19937& rng,
                       std::unordered_map<int, int>& idMap, float jitter = 0.0f);

// Fraction of the nodes of `a` but its root that `g` links to their copies
// (idMap as perturbedCopy made it).
double recoveredLinks(const BlobTree& a, const CorrespondenceGraph& g, const std::unordered_map<int, int>& idMap);

// A random tree of blends, unions and frames over skeletal primitives, with
// distinct, spread-out primitive positions; about `nodes` nodes.
BlobTree randomCreature(std::mt19937& rng, int nodes);

}  // namespace animorph::test
