#pragma once
// Convert to particles (docs/particles.md): fills the inside (f >= 0) of a field
// program -- a BlobTree actor, a character's stand-in, anything compiled to a
// FieldProgram -- with N to N + 1 % point primitives on a regular lattice,
// blended under one root: the spacing (and, when a step of the count jumps
// over that window, the lattice's phase) is searched for the lattice with the
// fewest points at or above N inside the shape. (Dropping the surplus would
// make N exact but leaves a cavity where an inner point goes: its neighbours'
// fields reach only half the threshold there.) Each point's radius of influence is radiusFactor lattice
// spacings; their common intensity is calibrated on a fine grid so that the
// particle version encloses the same volume as the shape at that grid, and a
// particle left alone still shows as a small ball (intensity > threshold when
// radiusFactor is about 1.25).
#include <atomic>
#include <functional>

#include "blobtree/blob_tree.h"
#include "field/field_program.h"
#include "util/result.h"

namespace animorph {

struct ConvertToParticlesSettings {
  int count = 4000;            // number of particles (the result: count..count + 1 %, unless the shape cannot hold so many); 1..1,000,000
  float radiusFactor = 1.25f;  // radius of influence / lattice spacing
  float stiffness = 3.0f;
  float threshold = 1.0f;      // threshold of the particle tree
  int calibrationCells = 4'000'000;  // cells of the calibration grid (at most)
  int threads = 0;
  std::function<void(float)> progress;
  const std::atomic<bool>* cancel = nullptr;
};

struct ConvertToParticlesReport {
  size_t particles = 0;
  float spacing = 0.0f;         // lattice spacing (m)
  float radius = 0.0f;          // radius of influence of each point
  float intensity = 0.0f;
  double shapeVolume = 0.0;     // inside the shape, counted on the calibration grid (m^3)
  double particleVolume = 0.0;  // inside the particle field, same grid
  bool cancelled = false;
};

struct ConvertToParticlesResult {
  BlobTree tree;  // root: blend "particles" (id 1) of points "p0".."pN-1" (ids 2..N+1)
  ConvertToParticlesReport report;
};

// Errors: an unbounded or empty shape, a count or factor out of range.
Result<ConvertToParticlesResult> convertToParticles(const FieldProgram& shape, const ConvertToParticlesSettings& s);

}  // namespace animorph
