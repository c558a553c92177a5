#pragma once
// A large skinned character for import and skinning benchmarks.
#include <cstddef>

#include "core/rig/character.h"

namespace animorph {

// A closed, capped tube 2 m long along +X (radius 0.1 m) with about
// targetTriangles triangles (at least a few hundred), skinned to a chain of 8
// bones with two influences per vertex blended between neighbouring bones,
// and a 2-second LINEAR "wave" clip. Deterministic.
Character makeDenseCharacter(size_t targetTriangles);

}  // namespace animorph
