#pragma once
// Solid (3D gradient) noise for post-deforming the transitional shape
// (docs/design.md §5): Perlin's improved noise with a fixed permutation, so baked
// frames are reproducible.
#include <cstdint>

#include <glm/glm.hpp>

#include "core/poly/mesh.h"

namespace animorph {

// Gradient noise in about [-1, 1], 0 at integer lattice points. Deterministic.
float solidNoise(const glm::vec3& p);

// Ken Perlin's permutation of 0..255 the noise hashes with (256 entries; the GPU
// polygoniser's noise pass reads the same table).
const uint8_t* solidNoisePermutation();

// Moves every vertex along its normal by amplitude * solidNoise(frequency * p)
// (metres; frequency in 1/m). The connectivity is unchanged. No-op at amplitude 0
// or when the mesh has no normals.
void displaceBySolidNoise(TriangleMesh& mesh, float amplitude, float frequency);

}  // namespace animorph
