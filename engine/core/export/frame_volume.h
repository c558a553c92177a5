#pragma once
// The level set of a baked frame (poly/level_set_sampler.h; io/vdb_export.h writes it), sampled
// on the grid the frame's mesh is polygonised on at the same resolution, so the two agree.
#include <atomic>
#include <optional>

#include "core/field/field_program.h"
#include "core/scene/morph_runtime.h"
#include "core/poly/level_set_sampler.h"
#include "core/util/result.h"

namespace animorph {

// A frame's level set, or none for a frame without an implicit field; or an error.
using FrameLevelSet = Result<std::optional<LevelSetVoxels>>;

// A morph's frame at timeSec: nullopt (not an error) for a frame that is a skinned mesh and has no
// implicit field (morphFrameField). threads: 0 = all; cancel may be null. colors: the surface
// colour at the voxels next to the surface too (LevelSetSettings::colors; a morph's from its
// colour program, MorphImplicitField::colorProgram; none when neither character has colours).
FrameLevelSet morphFrameLevelSet(const MorphRuntime& rt, double timeSec, int resolution,
                                 int threads, const std::atomic<bool>* cancel, bool colors = false);

// Any field polygonised with its own bounds (an animorphosis' C(t), a BlobTree): always a level set.
FrameLevelSet fieldLevelSet(const FieldProgram& program, int resolution, int threads,
                            const std::atomic<bool>* cancel, bool colors = false);

}  // namespace animorph
