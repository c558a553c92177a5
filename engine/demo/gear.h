#pragma once
// A procedural gear for demos and tests: a solid with several holes.
#include "core/rig/character.h"

namespace animorph {

// A spur gear standing in the XY plane (axis +Z), 0.7 m across, 0.08 m thick,
// its centre 0.36 m above the ground: 12 teeth, an axle hole and four windows
// between four spokes (genus 5 once coincident vertices are welded). Faces
// have their own vertices for crisp normals. Skinned to two bones: "hub"
// (inside the spokes) and its child "rim" (outside), blended along the spokes.
// One clip, "turn": the hub turns a full revolution in 4 s (LINEAR) while the
// rim flexes a few degrees back and forth (LINEAR). Material "bronze" (a base colour
// factor). Deterministic.
Character makeGearCharacter();

}  // namespace animorph
