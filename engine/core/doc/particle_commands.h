#pragma once
// Undoable particle edits of a BlobTree actor (docs/particles.md), for the
// inspector's Particles section and scripts. Each builder does the long work (a
// simulation, a conversion) on the caller's thread -- run it on a worker, with the
// settings' progress and cancel -- and returns one command replacing the actor's
// tree: Simulate and Convert are one undo step each.
#include <memory>
#include <string>

#include "doc/command.h"
#include "doc/project.h"
#include "particles/convert_to_particles.h"
#include "particles/particle_tree.h"

namespace animorph {

// Re-simulates the actor's point primitives with new settings (their positions at
// options.startSec, or at the end when reversed) and bakes them into their tracks.
// Errors name the actor and the reason; cancelled: an error "cancelled".
Result<std::unique_ptr<Command>> simulateParticlesCommand(const Project& p, const std::string& actorId,
                                                          const ParticleSettings& settings,
                                                          const ParticleBakeOptions& options,
                                                          ParticleBakeReport* report = nullptr);

// Replaces the actor's tree by about settings.count particles filling its shape at timeSec.
Result<std::unique_ptr<Command>> convertToParticlesCommand(const Project& p, const std::string& actorId,
                                                           double timeSec, const ConvertToParticlesSettings& settings,
                                                           ConvertToParticlesReport* report = nullptr);

}  // namespace animorph
