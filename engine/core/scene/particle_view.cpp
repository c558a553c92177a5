#include "core/scene/particle_view.h"

#include <algorithm>
#include <cstdio>

#include "core/math/bounds.h"

namespace animorph {

namespace {

// The draw's tree; the animorphosis' C(t) snapshot stays alive in its cache until the next frame's.
const BlobTree* drawTree(const BlobDraw& d, const Project& project) {
  if (auto own = d.ownTree()) return own.get();
  const Actor* a = project.findActor(d.actorId);
  return a && a->kind == ActorKind::BlobTree ? &a->blobTree : nullptr;
}

// Whether the tree has at least `enough` particles (points reached through operators only).
bool hasParticles(const BlobTree& tree, size_t enough) {
  size_t c = 0;
  forEachParticleNode(tree.root, [&](const BlobNode&) { ++c; });
  return c >= enough;
}

}  // namespace

ParticleDraw particleDraw(const BlobDraw& draw, const Project& project, size_t minParticles) {
  ParticleDraw out;
  out.actorId = draw.actorId;
  out.model = draw.model;
  const BlobTree* tree = drawTree(draw, project);
  if (!tree || !hasParticles(*tree, minParticles)) return out;
  TreeParticles tp = treeParticles(*tree, draw.treeTimeSec);
  out.centres = std::move(tp.set.position);
  out.radii = std::move(tp.set.radius);
  return out;
}

bool particlesBelowGrid(const ParticleDraw& draw, int resolution, float* cellSize, float* medianRadius) {
  if (resolution <= 0 || draw.centres.empty()) return false;
  Bounds b;
  for (size_t i = 0; i < draw.centres.size(); ++i) {
    const float r = i < draw.radii.size() ? draw.radii[i] : 0.0f;
    b.add(draw.centres[i] - glm::vec3(r));
    b.add(draw.centres[i] + glm::vec3(r));
  }
  const glm::vec3 size = b.size();
  const float cell = std::max({size.x, size.y, size.z}) / float(resolution);
  std::vector<float> radii = draw.radii;
  radii.resize(draw.centres.size(), 0.0f);
  std::nth_element(radii.begin(), radii.begin() + long(radii.size() / 2), radii.end());
  const float median = radii[radii.size() / 2];
  if (cellSize) *cellSize = cell;
  if (medianRadius) *medianRadius = median;
  // A median of 0: points that show only together (each alone stays under the threshold, as in a
  // creature's blend), not separate particles: their surface is what the grid must resolve.
  return median > 0.0f && median < 0.5f * cell;
}

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
    const BlobTree* tree = drawTree(d, project);
    if (!tree || !hasParticles(*tree, settings.minParticles)) {
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
