#pragma once
// The editor's policy for particle systems in the viewport (docs/particles.md): a BlobTree draw
// whose tree has many particles (core/scene/particle_draw.h) is shown as its particles -- each at
// its centre, the size of its visible radius -- while its time or its tree changes (scrubbing,
// playing) and for holdSec after, and then until its polygonised surface has caught up: the
// surface is not polygonised at every frame of a scrub, and a stale surface is not shown in place
// of the moving particles. The renderer draws ParticleDraw as spheres
// (gpu/render/particle_spheres.h).
//
// A particle system whose grid would lose its particles (particlesBelowGrid: median visible radius
// below half a cell of the surface's grid) is drawn as particles even while its time holds (and in
// screenshots), and note() says so; its surface comes back once the particles gather.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/project/project.h"
#include "core/scene/particle_draw.h"
#include "core/scene/scene_frame.h"

namespace animorph {

struct ParticleViewSettings {
  bool enabled = true;       // Preferences::particleView
  size_t minParticles = 64;  // fewer particles: always the surface
  double holdSec = 0.3;      // the surface is polygonised once the time has held this long
  bool holding = false;      // the user holds the time (drags the timeline, plays): particles stay
  bool settle = false;       // a screenshot: no particles for moving systems (only for those below the grid)
  int surfaceResolution = 0; // the refined surface's grid (cells along the longest side); 0: no check
};

class ParticleView {
 public:
  // Before the surface previews are updated: takes out of frame.blobs (and returns) the draws of
  // particle systems that moved less than holdSec before nowSec, so no surface is polygonised for them.
  std::vector<ParticleDraw> takeMoving(SceneFrame& frame, const Project& project, double nowSec,
                                       const ParticleViewSettings& settings);
  // After the previews are updated: takes out (and returns) the held particle systems whose surface
  // is not ready (surfaceReady(actorId) false: still computing its shape), which were moving before.
  std::vector<ParticleDraw> takeUnready(SceneFrame& frame, const Project& project,
                                        const std::function<bool(const std::string&)>& surfaceReady);
  // Some draw was shown as particles by the last calls (it turns into its surface without input:
  // keep drawing frames).
  bool pending() const { return pending_; }
  // Names the particle systems drawn as particles because the surface's grid would lose them,
  // with the cell and particle sizes; empty when none is.
  const std::string& note() const { return note_; }

 private:
  struct Seen {
    double treeTimeSec = 0.0;
    const void* tree = nullptr;  // a draw's own tree, by its preview source (a new pointer when it changes)
    double movedAt = -1e9;
    bool waiting = false;            // held, its surface not shown yet
  };
  std::map<std::string, Seen> seen_;
  bool pending_ = false;
  std::string note_;
};

}  // namespace animorph
