#pragma once
// Physically-based animorphosis (docs/particles.md): a shape made of particles
// explodes (A(t): the explosion simulated forward from the shape) and re-forms
// out of a swirling vortex (B(t): a vortex simulated forward from the same rest
// positions -- or from those of gatheringRest, another shape -- written backwards
// in time, so it ends at the rest positions). A and B
// are copies of the same particle tree, every particle linked to itself in the
// correspondence graph (identity links), and the ordinary animorphosis morphs
// them with s(t) over [startSec, startSec + duration]: at the start C is A at rest,
// at the end B at rest.
#include <optional>

#include "core/animorphosis/correspondence.h"
#include "core/blobtree/blob_tree.h"
#include "core/particles/particle_tree.h"

namespace animorph {

struct ParticleAnimorphosisSettings {
  ParticleSettings explosion;  // A(t); its duration is the interval's
  ParticleSettings vortex;     // B(t), before reversal; its duration is set to the explosion's
  double startSec = 0.0;
  float tolerance = 3e-3f;     // bake tolerance of both (m)
  double quantum = 0.0;        // key rounding of both (ParticleBakeOptions)
  // Re-forming into another shape: the same particles resting where B(t) ends (reformIntoShape,
  // particles/particle_transport.h); empty: B ends where A starts.
  std::optional<BlobTree> gatheringRest;
};

struct ParticleAnimorphosis {
  BlobTree exploding;  // A
  BlobTree gathering;  // B
  CorrespondenceGraph graph;  // every point of A to the point of B with the same id
  double startSec = 0.0, endSec = 0.0;
  ParticleBakeReport explosionReport, vortexReport;
  bool cancelled = false;
};

// From a tree of point primitives at rest (convertToParticles). Errors: those of
// the simulation; a tree without points.
Result<ParticleAnimorphosis> makeParticleAnimorphosis(const BlobTree& particles,
                                                      const ParticleAnimorphosisSettings& settings);

// The identity links of a tree's points (each point of A to the same id in B).
CorrespondenceGraph identityPointLinks(const BlobTree& tree);

}  // namespace animorph
