#pragma once
// Undoable particle edits of a BlobTree actor (docs/particles.md), for the
// inspector's Particles section and scripts. Each builder does the long work (a
// simulation, a conversion) on the caller's thread -- run it on a worker, with the
// settings' progress and cancel -- and returns one command replacing the actor's
// tree: Simulate and Convert are one undo step each.
#include <memory>
#include <string>

#include "core/doc/command.h"
#include "core/project/project.h"
#include "core/rig/character.h"
#include "core/particles/convert_to_particles.h"
#include "core/particles/particle_animorphosis.h"
#include "core/particles/particle_transport.h"
#include "core/particles/particle_tree.h"

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

// Convert to particles from a glTF character actor (docs/particles.md): its stand-in (the morph's
// stand-in of the actor, or one fitted now when it has none) or its skinned meshes
// (particles/character_shape.h), posed at scene time timeSec, filled with particles as a new
// BlobTree actor "NAME particles" (a fresh id, the character's transform, not looping) to add with
// addActorCommand (one undo step); the character is left as it is. A mesh with holes is still
// filled (particles/mesh_inside.h: the majority of three rays) and its boundary edges reported.
// Errors name the actor and the reason (no glTF actor, no triangle, an empty stand-in);
// cancelled: an error "cancelled".
enum class ParticleSource { Standin, Mesh };
const char* particleSourceName(ParticleSource s);  // "standin", "mesh"
bool particleSourceFromName(const std::string& name, ParticleSource& out);

struct CharacterParticlesReport {
  ConvertToParticlesReport convert;
  bool standinFitted = false;  // the actor had no stand-in: one was fitted for the conversion
  size_t triangles = 0;        // mesh: triangles filled
  size_t boundaryEdges = 0;    // mesh: 0 when closed
  double meshVolume = 0.0;     // mesh: enclosed volume (m^3), meaningful when closed
};

Result<Actor> characterParticlesActor(const Project& p, const std::string& actorId, const Character& character,
                                      double timeSec, ParticleSource from, const ConvertToParticlesSettings& settings,
                                      CharacterParticlesReport* report = nullptr);

// Explode and re-form (docs/particles.md): the actor's particles explode (settings.explosion) and
// gather out of a vortex played backwards (settings.vortex) -- back into their own rest positions
// or, with a reformInto actor id, into that BlobTree actor's shape at settings.startSec (its tree's
// own space; particles/particle_transport.h) -- as the project's animorphosis: the actor's tree
// becomes A (exploding, not looping), a new actor "NAME gathering" B (the actor's transform), and
// the animorphosis morphs A into B over the simulated interval with identity links.
struct ParticleReformEdit {
  std::string actorId;
  BlobTree exploding;
  Actor gathering;
  AnimorphosisSetup animorphosis;
};

struct ParticleReformReport {
  size_t particles = 0;
  size_t keys = 0;          // A's and B's
  float maxError = 0.0f;    // of both bakes (m)
  bool reformed = false;    // gathers into another shape
  ParticleTransportReport transport;
  double startSec = 0.0, endSec = 0.0;
};

// The animorphosis settings the CLI and the editor start from: explosion as given, and a vortex of
// the same settings without explosion and gravity.
ParticleAnimorphosisSettings reformSettings(const ParticleSettings& settings, const ParticleBakeOptions& bake);

// Errors name the actor and the reason (no BlobTree actor, the target is the actor itself, no
// points, a shape that does not hold the particles); cancelled (settings.explosion.cancel, which
// also stops the re-forming's assignment; the vortex's own cancel stops its simulation): an error
// "cancelled".
Result<ParticleReformEdit> particleReformEdit(const Project& p, const std::string& actorId,
                                              const ParticleAnimorphosisSettings& settings,
                                              const std::string& reformInto = {}, ParticleReformReport* report = nullptr);
// Applies an edit made for p (or a project with the same actors).
void applyParticleReform(Project& p, const ParticleReformEdit& edit);
// particleReformEdit as one undoable command ("Explode and re-form NAME").
Result<std::unique_ptr<Command>> particleReformCommand(const Project& p, const std::string& actorId,
                                                       const ParticleAnimorphosisSettings& settings,
                                                       const std::string& reformInto = {},
                                                       ParticleReformReport* report = nullptr);

}  // namespace animorph
