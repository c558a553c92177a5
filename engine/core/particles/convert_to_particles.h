#pragma once
// Convert to particles (docs/particles.md): fills the inside of a shape -- a
// field program's f >= 0 (a BlobTree actor, a character's stand-in, anything
// compiled to a FieldProgram), or a closed triangle mesh's inside
// (particles/mesh_inside.h) -- with N to N + 1 % point primitives on a regular lattice,
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
#include <cstdint>
#include <functional>
#include <vector>

#include "core/blobtree/blob_tree.h"
#include "core/field/field_program.h"
#include "core/util/result.h"

namespace animorph {

// Sample points origin + spacing * (i, j, k), 0 <= (i, j, k) < dims.
struct SampleLattice {
  glm::vec3 origin{0.0f};
  float spacing = 1.0f;
  glm::ivec3 dims{0};
  size_t size() const { return size_t(dims.x) * size_t(dims.y) * size_t(dims.z); }
  glm::vec3 point(int x, int y, int z) const { return origin + spacing * glm::vec3(x, y, z); }
  size_t index(int x, int y, int z) const { return size_t(x) + size_t(dims.x) * (size_t(y) + size_t(dims.y) * size_t(z)); }
};

// What convertToParticles fills: a bounded shape, given by a box holding all of its inside and an
// inside test of every point of a lattice at once (inside[lattice.index(i, j, k)] = 1 where the
// point is inside, else 0). The same test serves the lattice search and the volume calibration,
// whatever the shape is. The test may run in parallel itself (it is called from a TBB arena).
struct ParticleShape {
  Bounds bounds;
  std::function<std::vector<uint8_t>(const SampleLattice&)> insideOnLattice;
};

// A field program's inside (f >= 0) as a ParticleShape; program must outlive the result.
// Errors: an unbounded program.
Result<ParticleShape> fieldParticleShape(const FieldProgram& program);

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
Result<ConvertToParticlesResult> convertToParticles(const ParticleShape& shape, const ConvertToParticlesSettings& s);
// The same for a field program's inside (fieldParticleShape).
Result<ConvertToParticlesResult> convertToParticles(const FieldProgram& shape, const ConvertToParticlesSettings& s);

}  // namespace animorph
