#pragma once
// The animorphosis demo creatures (issue 18, docs/animorphosis.md "The demo"),
// built in code as animated BlobTrees of one family:
//  * a walking biped dinosaur: a hierarchy of 20 joint frames (flight, pelvis,
//    chest, back, neck, head, jaw, two arms with elbows, two legs with knee,
//    ankle and toe, tail), every body part a bundle of spline-of-nodes fibres
//    (a Catmull-Rom spline of copies of one point primitive), a tail whose
//    fibres have animated control points, a belly that breathes through the
//    radius tracks of its fibres' points, and quills, teeth and claws;
//  * a flying dragon: the same body and joint names (slimmer, longer neck and
//    tail, legs tucked, flying above the ground), horns, and two wings that
//    flap, each an arm and a hand of fibre bones holding a membrane: a union of
//    Coons-patch meta-primitives tiling a billowing surface.
// Both in colour (every primitive's colour parameter): the dinosaur olive green with darker
// stripes, a cream belly, orange quills and ivory teeth and claws; the dragon crimson with darker
// stripes, a golden belly, orange wing membranes and ivory horns.
// Both clips loop (the dinosaur every kDinosaurLoopSec, the dragon every
// kDragonLoopSec): every animated track has its last key at the loop time.
#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"

namespace animorph {

inline constexpr double kDinosaurLoopSec = 2.0;
inline constexpr double kDragonLoopSec = 1.0;

BlobTree makeDinosaur();
BlobTree makeDragon();

// The artist's graph between the two: every node of the shared body (joint
// frames, body parts and their fibres) linked by name to the dragon's; the
// dinosaur's quills, teeth and claws and the dragon's wings and horns left
// unlinked, so they shrink into the body or grow out of it (the wings out of
// the back). Overrides of s: the back (so the wings) and the legs go faster,
// the flight frame (the creature's height above the ground) holds s at 0 for
// the first third and the pelvis link gives the body the global s again.
CorrespondenceGraph dinosaurToDragonGraph(const BlobTree& dinosaur, const BlobTree& dragon);

}  // namespace animorph
