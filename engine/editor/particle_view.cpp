#include "editor/particle_view.h"

#include <cstdio>

namespace animorph {

std::vector<ParticleDraw> ParticleView::takeMoving(SceneFrame& frame, const Project& project, double nowSec,
                                                   const ParticleViewSettings& settings) {
  pending_ = false;
  note_.clear();
  std::vector<ParticleDraw> out;
  if (!settings.enabled) {
    seen_.clear();
    return out;
  }
  std::map<std::string, Seen> seen;
  std::vector<BlobDraw> kept;
  for (BlobDraw& d : frame.blobs) {
    if (!particleTree(d, project, settings.minParticles)) {
      kept.push_back(std::move(d));
      continue;
    }
    auto it = seen_.find(d.actorId);
    Seen s = it != seen_.end() ? it->second : Seen{};
    const void* own = d.source.get();
    const bool first = it == seen_.end();
    if (settings.holding || (!first && (s.treeTimeSec != d.treeTimeSec || s.tree != own))) {
      s.movedAt = nowSec;
      s.waiting = true;
    }
    s.treeTimeSec = d.treeTimeSec;
    s.tree = own;
    if (settings.settle) s.waiting = false;  // a screenshot waits for the surface itself
    seen[d.actorId] = s;
    if (!settings.settle && nowSec - s.movedAt < settings.holdSec) {
      out.push_back(particleDraw(d, project, settings.minParticles));
      pending_ = true;
      continue;
    }
    // Holding still: the surface, unless its grid would lose the particles.
    ParticleDraw pd = particleDraw(d, project, settings.minParticles);
    float cell = 0.0f, radius = 0.0f;
    if (particlesBelowGrid(pd, settings.surfaceResolution, &cell, &radius)) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s%s: particles (%.2g m) below the %d^3 grid (%.2g m cells), as spheres",
                    note_.empty() ? "" : "; ", d.actorId.c_str(), double(radius), settings.surfaceResolution,
                    double(cell));
      note_ += buf;
      s.waiting = false;  // no surface to wait for
      seen[d.actorId] = s;
      out.push_back(std::move(pd));
    } else {
      kept.push_back(std::move(d));
    }
  }
  seen_ = std::move(seen);
  frame.blobs = std::move(kept);
  return out;
}

std::vector<ParticleDraw> ParticleView::takeUnready(SceneFrame& frame, const Project& project,
                                                    const std::function<bool(const std::string&)>& surfaceReady) {
  std::vector<ParticleDraw> out;
  std::vector<BlobDraw> kept;
  for (BlobDraw& d : frame.blobs) {
    auto it = seen_.find(d.actorId);
    if (it != seen_.end() && it->second.waiting) {
      if (surfaceReady(d.actorId)) {
        it->second.waiting = false;
      } else {
        out.push_back(particleDraw(d, project, 1));
        pending_ = true;
        continue;
      }
    }
    kept.push_back(std::move(d));
  }
  frame.blobs = std::move(kept);
  return out;
}

}  // namespace animorph
