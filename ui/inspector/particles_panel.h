#pragma once
// The inspector's Particles section of a BlobTree actor (docs/particles.md, docs/editor.md):
// *Convert to particles* (the count chosen here) for any BlobTree actor -- and for a glTF
// character actor, from its stand-in or its posed mesh, into a new BlobTree actor
// (doc/particle_commands.h characterParticlesActor) --, and for a BlobTree actor whose tree
// has point primitives (a particle system) the simulation's forces, seed, rate, start and
// duration with a Simulate button, and Explode and re-form: the particles explode and gather back
// out of a vortex into their own shape or into another BlobTree actor's, as the project's
// animorphosis (doc/particle_commands.h particleReformCommand). The panel only edits its settings and asks: EditorUI runs the
// asked operation as a background job (progress, Cancel) and applies its result as one undoable
// command (doc/particle_commands.h).
#include <string>

#include "core/doc/document.h"
#include "core/doc/particle_commands.h"
#include "core/particles/particle_tree.h"

namespace animorph {

enum class ParticleRequest { None, Simulate, Convert, Reform };

struct ParticlesPanelState {
  std::string actorId;        // whose tree the settings below were set up for
  ParticleSettings settings;  // forces, seed, rate, duration (progress and cancel unused here)
  ParticleBakeOptions bake;   // start time, tolerance, reverse
  int convertCount = 4000;    // Convert to particles
  ParticleSource convertFrom = ParticleSource::Standin;  // a character actor's: its stand-in or its mesh
  std::string reformInto;     // Explode and re-form: the BlobTree actor to gather into; empty: its own shape
  bool busy = false;          // set by EditorUI: a background job runs (the buttons are disabled)
  // What the user asked for this frame; EditorUI takes it (and sets it back to None).
  ParticleRequest request = ParticleRequest::None;
};

// The number of point primitives of tree (its particles).
size_t countParticles(const BlobTree& tree);

// Settings for a tree seen for the first time: the bake starts at the first key of its points'
// centre tracks and lasts until the last one (3 s when they are not animated), the explosion
// at the particles' centroid at the start.
void resetParticleSettings(const BlobTree& tree, ParticlesPanelState& st);

// Draws the section (inside the inspector window) for actorId: a BlobTree actor's whole section, a
// glTF character actor's Convert to particles (from: stand-in | mesh) only.
void drawParticlesSection(const Document& doc, const std::string& actorId, ParticlesPanelState& st);

}  // namespace animorph
