#pragma once
// The statue demo (resources/demo/statue.animorph; docs/particles.md): a procedural
// statue -- a standing figure with raised arms on a round pedestal, built from
// skeletal primitives -- converted to particles, which an explosion scatters over
// the ground and a time-reversed vortex gathers back into the statue.
#include "core/project/project.h"
#include "core/particles/convert_to_particles.h"
#include "core/particles/particle_animorphosis.h"
#include "core/util/result.h"

namespace animorph {

// The statue as a smooth BlobTree (about 1.9 m tall, standing on y = 0).
BlobTree makeStatue();

struct StatueDemoOptions {
  int particles = 3000;
  double holdSec = 0.5;       // the statue stands still before the explosion and after it re-forms
  double durationSec = 4.0;   // of the animorphosis
  double rateHz = 100.0;      // simulation steps (1/100 s: key times print short)
  float tolerance = 6e-3f;    // bake tolerance (m; a cell of a 128^3 grid over the statue is 16 mm)
  double quantum = 1e-4;      // key values rounded to 0.1 mm (slopes to 1 mm/s)
};

// The explosion and vortex settings the demo uses (centred on the statue).
ParticleAnimorphosisSettings statueDemoSettings(const StatueDemoOptions& options);

struct StatueDemo {
  Project project;       // actors "exploding" and "gathering", the animorphosis between them
  ParticleAnimorphosis animorphosis;
  ConvertToParticlesReport conversion;
};

// The project, checked (checkAnimorphosis) before it is returned.
Result<StatueDemo> makeStatueDemo(const StatueDemoOptions& options = {});

}  // namespace animorph
