#pragma once
// The particle view's drawing (scene/particle_view.h; docs/particles.md): each particle as a small
// marker -- three crossed segments along the world axes, as long as its visible diameter -- in the
// depth-tested line batch, so a few thousand particles cost a few thousand segments a frame (no
// polygonisation while scrubbing).
#include "render/line_batch.h"
#include "scene/particle_view.h"

namespace animorph::gpu {

// Appends the markers of draw (in the world, through draw.model) to lines in rgba.
void addParticleMarkers(const ParticleDraw& draw, uint32_t rgba, LineBatch& lines);

}  // namespace animorph::gpu
