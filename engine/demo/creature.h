#pragma once
// A procedural lizard-like quadruped for demos and tests (the repository
// carries no third-party art).
#include "core/rig/character.h"

namespace animorph {

// A smooth, closed genus-0 skinned surface (a few thousand triangles) built
// as the boundary of a smooth union of tapered capsules around 15 bones
// (hips, chest, neck, head, three tail bones, four legs of two bones each),
// with distance-based weights blended across neighbouring bones and one clip,
// "walk": a 2-second looping diagonal-pair walk cycle (legs LINEAR, body
// and tail CUBICSPLINE). Facing +Z, feet on y = 0, metres. Coloured by a generated
// 128 x 64 scales texture (dark banded back, green flanks, pale belly) on a side
// projection of the body (material "scales"). Deterministic.
Character makeCreatureCharacter();

}  // namespace animorph
