#pragma once
// The stand-in core of a transition (docs/morph.md, "Continuity"): during the
// collapse (A -> B) and the expansion (C -> D) the actor's posed stand-in is
// polygonised inside the transitioned mesh, scaled by the transition's progress,
// and drawn with it. A mesh lying on its stand-in does not enclose the
// stand-in's volume (closest-point projection folds it: the gear's windows run
// through the stand-in's inside, a flat plate's faces gather on the rim), so
// switching at C from the polygonised stand-in to the mesh alone halved the
// volume in one frame. With the core, the shape at C + 0 is the stand-in itself
// and the target grows out of it while the core melts into its skeleton:
//   core potential = c(v) h_K(p),  c = 1/K + (1 - 1/K) (1 - easing(v)) (expansion;
//   easing(v) instead of 1 - easing(v) for the collapse), v = u / kStandinCoreSpan
//   (expansion; 1 - (1 - u) / kStandinCoreSpan for the collapse), clamped to [0, 1]
// with h_K the interpolation's bound (standin_morph/morph_field.h; the project's K, or
// kDefaultInterpolationBound when unbounded), capped at c K T: the core equals
// the stand-in exactly at c = 1 (the morph's end field at C, its start field at
// B) and shrinks into its skeleton's densest points, gone at c = 1/K, i.e. half
// way through the expansion (it grows over the second half of the collapse): the
// core is needed only while the mesh is folded onto the stand-in, and where it
// fills what the folded mesh leaves open (the gear's windows) it shows; lasting the
// whole expansion it lingered there as pills until the last frames before D
// (docs/morph.md, "The stand-in core"). Each segment of the
// core also shortens about its middle, to s = (c - 1/K) / (1 - 1/K) of its
// length (1 at C / B): a segment whose end lies outside the mesh (the gear's
// outer chords end on its teeth's circle, beyond the rim between two teeth)
// draws its end back inside instead of melting onto it in plain view.
// A BlobTree side has no transition and no core.
#include <optional>

#include "core/scene/morph_runtime.h"

namespace animorph {

// The share of a transition the core lasts, next to the implicit stage: it melts
// over the first kStandinCoreSpan of the expansion and grows over the last
// kStandinCoreSpan of the collapse (u in c(u) above is the core's own progress).
inline constexpr double kStandinCoreSpan = 0.5;

// c(u) above, for the collapse (expand false) or the expansion, u clamped to [0, 1].
float standinCoreScale(const MorphSetup& setup, bool expand, double u);

// The core's field at scene time timeSec and transition progress u: nullopt
// when there is none (a BlobTree side, or the core has melted away).
std::optional<MorphImplicitField> standinCoreField(const MorphRuntime& rt, double timeSec, bool expand, double u);

// Polygonises the core of fr (a collapse or expansion frame: its stage, time
// and progress) at settings' resolution and appends it to fr.mesh as a second
// shell (fr.coreTriangles counts its triangles, fr.polygonize its stats). No
// core: fr unchanged. Errors: polygonisation failed.
Status appendStandinCore(const MorphRuntime& rt, MorphFrame& fr, const MorphFrameSettings& settings);

}  // namespace animorph
