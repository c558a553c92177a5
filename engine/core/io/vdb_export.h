#pragma once
// Level sets as OpenVDB files (.vdb), for Houdini, Blender and other volume tools. The one file of
// the project that includes OpenVDB is vdb_export.cpp (library animorph_vdb): this header has no
// OpenVDB types.
#include <string>

#include "core/poly/level_set_sampler.h"
#include "core/util/result.h"

namespace animorph {

// Writes the band as one float grid named gridName ("surface", the name Houdini's and Blender's
// SDF tools look for): grid class level set, background = band.background, voxel (i, j, k)'s
// centre at band.origin + band.voxelSize * (i, j, k) (a linear transform), the inside filled by
// a signed flood fill (negative), blosc-compressed. The band is redistanced first: voxels within
// one voxel of the surface keep their (first-order) distances, the others get OpenVDB's fast
// sweeping's (tools::sdfToSdf), clamped to the background (docs/export.md has the measurements).
// With colours (LevelSetVoxels::colorVoxel non-empty), a second grid "Cd" beside it: a
// float-vector grid of the linear RGB surface colour at the voxels next to the surface
// (Houdini's colour attribute name), the same transform. Serialised in memory, then written atomically (a temporary beside path, renamed: no
// half-written file). Errors name the path and the reason (the folder is missing or not
// writable, the band is cancelled or has no valid voxel size).
Status writeVdbLevelSet(const LevelSetVoxels& band, const std::string& path, const std::string& gridName = "surface");

}  // namespace animorph
