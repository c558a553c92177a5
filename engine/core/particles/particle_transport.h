#pragma once
// Re-forming into another shape (docs/particles.md): each particle of one shape is given one place
// in a second shape's volume (the points of convertToParticles of that shape, as many as there are
// particles), so that the paths between them do not cross needlessly. The assignment minimises the
// sum of squared distances approximately: a greedy start (both sets sorted along their common
// principal axis and paired rank by rank), improved by pairwise exchanges among near neighbours
// until no exchange of two particles' places shortens the sum. For the squared cost two
// straight paths a -> b, a' -> b' that an exchange would shorten are the ones that cross or pass
// each other; none such pair is left among the neighbours examined.
#include <atomic>
#include <vector>

#include <glm/glm.hpp>

#include "core/blobtree/blob_tree.h"
#include "core/field/field_program.h"
#include "core/particles/convert_to_particles.h"
#include "core/util/result.h"

namespace animorph {

struct ParticleTransportSettings {
  int neighbours = 24;      // exchanges are tried with this many nearest particles of each
  int maxSweeps = 50;       // sweeps over all particles (stops earlier once a sweep changes nothing)
  const std::atomic<bool>* cancel = nullptr;
};

struct ParticleTransportReport {
  double greedyCost = 0.0;  // sum of squared distances of the greedy start (m^2)
  double cost = 0.0;        // after the exchanges
  int sweeps = 0;
  size_t exchanges = 0;
  bool cancelled = false;
};

struct ParticleTransport {
  std::vector<int> target;  // target[i]: the place of particle i (a permutation of 0..n-1)
  ParticleTransportReport report;
};

// Errors: sets of different sizes, non-finite positions.
Result<ParticleTransport> assignParticles(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to,
                                          const ParticleTransportSettings& settings = {});

// Sum of squared distances of an assignment.
double transportCost(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to,
                     const std::vector<int>& target);

// A copy of a particle tree (points in depth-first order, as treeParticles lists them) whose points
// rest at places[target[i]]: constant centre tracks. Errors: a count that is not the tree's points'.
Result<BlobTree> reformedParticles(const BlobTree& particles, const std::vector<glm::vec3>& places,
                                   const std::vector<int>& target);

// Exactly n places filling a shape's volume: the points of convertToParticles (settings.count
// raised until there are at least n), thinned evenly to n. Errors: those of the conversion.
Result<std::vector<glm::vec3>> particlePlaces(const FieldProgram& shape, size_t n, ConvertToParticlesSettings settings);

// The particles of a tree re-formed into a shape: its points assigned (assignParticles from their
// positions at timeSec) to particlePlaces of the shape and resting there (reformedParticles).
Result<BlobTree> reformIntoShape(const BlobTree& particles, double timeSec, const FieldProgram& shape,
                                 const ConvertToParticlesSettings& places = {},
                                 const ParticleTransportSettings& transport = {},
                                 ParticleTransportReport* report = nullptr);

}  // namespace animorph
