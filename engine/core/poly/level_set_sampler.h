#pragma once
// A narrow-band signed distance sampled from an implicit field, on the polygoniser's grid: the
// voxels of a level set (io/vdb_export.h writes them as an OpenVDB file). docs/export.md
// describes the conversion: the field value f = p - T (>= 0 inside) is not a distance; near its
// zero set the first-order estimate d = -f / |grad f| is one (exact for a linear field; measured
// within 0.1-0.25 voxel of the real distance next to the surface at 32^3-64^3, but up to 1-1.5
// voxels off 3 voxels away: io/vdb_export.h redistances that part of the band). World units,
// negative inside.
#include <atomic>
#include <vector>

#include <glm/glm.hpp>

#include "core/field/field_program.h"
#include "core/poly/polygonizer.h"
#include "core/util/result.h"

namespace animorph {

struct LevelSetSettings {
  // The grid: the one polygonize() would use with these settings (resolution, bounds,
  // marginCells), so voxel (i, j, k) is the polygoniser's grid corner (i, j, k). threads and
  // cancel are used as polygonize() uses them; progress is not called.
  PolygonizeSettings grid;
  // Half-width of the band in voxels: voxels whose distance is below halfWidth * voxelSize are
  // stored (OpenVDB's tools expect 3; under 1 the zero crossing can lose its neighbours).
  float halfWidth = 3.0f;
  // The solid-noise displacement the polygonised mesh gets (poly/solid_noise.h): the level set
  // is moved by the same amount (d - amplitude * noise(frequency * p)); 0: none.
  float noiseAmplitude = 0.0f;
  float noiseFrequency = 0.0f;
  // Surface colour beside the distance (field/surface_color.h) at the voxels within
  // kColorBandVoxels of the surface: LevelSetVoxels::colorVoxel / color. Off: none.
  bool colors = false;
  // With colors: the program the colours are evaluated on instead of the sampled one (as
  // PolygonizeSettings::colorProgram: a morph's stand-ins split into their colour samples).
  // Null: the program itself.
  const FieldProgram* colorProgram = nullptr;
};

// Voxels whose |distance| is below this many voxel sizes get a colour (LevelSetSettings::colors):
// every voxel a trilinear lookup at the surface reads (the surface lies within one voxel of
// the eight corners around it, each within sqrt(3) voxels of the surface).
constexpr float kColorBandVoxels = 2.0f;

struct LevelSetVoxels {
  glm::vec3 origin{0.0f};  // world position of voxel (0, 0, 0)'s centre
  float voxelSize = 1.0f;  // world units
  float background = 3.0f; // halfWidth * voxelSize: the distance beyond the band (outside)
  int cells[3] = {0, 0, 0};  // the polygoniser's grid (voxels 0..cells[a] along axis a)
  // The band, in the order of 8^3-voxel blocks then x fastest: index and signed distance (world
  // units, negative inside, |distance| < background).
  std::vector<glm::ivec3> index;
  std::vector<float> distance;
  // With LevelSetSettings::colors: the positions in index/distance of the voxels that have a
  // colour (|distance| < kColorBandVoxels * voxelSize, increasing) and their colours (linear
  // RGB of the surface colour at the voxel's centre). Empty without colours.
  std::vector<uint32_t> colorVoxel;
  std::vector<glm::vec3> color;
  size_t pointsEvaluated = 0;  // field evaluations (with gradient)
  bool cancelled = false;      // the cancel flag was set: the band is incomplete
};

// Samples the band of f = 0 of the program. Beyond the grid's box the level set is cut by it as
// the polygoniser closes a surface cut by its grid (max with the box's signed distance), so an
// unbounded field (space-time blending) gives a closed level set. A field inside nowhere gives an
// empty band. With settings.colors, the voxels next to the surface get the surface colour
// (a second pass after the band, SurfaceColorEvaluator with the grid's threads). Errors: as polygonizeGrid's (bad resolution, an unbounded field without bounds),
// halfWidth outside 1..16.
Result<LevelSetVoxels> sampleLevelSet(const FieldProgram& program, const LevelSetSettings& settings);

}  // namespace animorph
