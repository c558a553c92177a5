#pragma once
// How a FieldProgram changed between two frames of one animation, for the polygoniser's temporal
// coherence (poly/polygonizer.h, PolygonizeHistory): whether two programs have the same structure,
// which primitives changed at all, and a bound on how much each primitive's change can move the
// program's field (docs/design.md §6, "temporal coherence").
#include <cstdint>
#include <vector>

#include "core/field/field_program.h"

namespace animorph {

// Operators, operator parameters, threshold and primitive counts equal: the programs differ at
// most in primitive data and maps.
bool sameStructure(const FieldProgram& a, const FieldProgram& b);

// Per global primitive id of `now` (same structure as `prev`): 1 where its field may differ, its
// data, its bound or a map above it being not exactly the same (compared value by value).
std::vector<uint8_t> changedPrimitives(const FieldProgram& now, const FieldProgram& prev);

// Per global primitive id of `now` (same structure as `prev`): an upper bound on
// sup_x |f_now(x) - f_prev(x)| that this primitive's change alone can cause in the whole program's
// field f, 0 for a primitive that did not change at all. The bound is the primitive's own change
// (skeletal primitives g = I (1 - (d/R)^2)^k: |dI| + max(I) S_k (D + |dR|) / min(R), with D a
// bound on how far its skeleton moved and S_k the kernel's steepest slope) times the Lipschitz
// constants of the operators above it (blend, union, intersection, hyper-blend, difference: 1;
// R-functions: 2). Under affine maps that changed (frames), the primitive is compared in world
// space when every map above it is a similarity (rotation, translation, uniform scale).
// Infinite where no bound is known: a warp or a non-uniform scale above it changed, the skeleton kind,
// stiffness or curve length changed, stiffness below 1, a convolution or capsule primitive that
// changed, a remap or bounded blend above a changed primitive. Curve skeletons are bounded through
// their control points (Catmull-Rom: twice the largest control-point move) against the exact
// distance to the curve. The field change at a point is at most the sum of these bounds over the
// primitives that reach it in either frame.
std::vector<float> primitiveChangeBounds(const FieldProgram& now, const FieldProgram& prev);

}  // namespace animorph
