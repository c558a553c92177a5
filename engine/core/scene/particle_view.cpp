#include "scene/particle_view.h"

namespace animorph {

namespace {

const BlobTree* drawTree(const BlobDraw& d, const Project& project) {
  if (d.tree) return d.tree.get();
  const Actor* a = project.findActor(d.actorId);
  return a && a->kind == ActorKind::BlobTree ? &a->blobTree : nullptr;
}

size_t countPoints(const BlobNode& n, size_t enough) {
  size_t c = n.type == NodeType::Point ? 1 : 0;
  for (const BlobNode& ch : n.children) {
    if (c >= enough) break;
    c += countPoints(ch, enough - c);
  }
  return c;
}

}  // namespace

ParticleDraw particleDraw(const BlobDraw& draw, const Project& project, size_t minParticles) {
  ParticleDraw out;
  out.actorId = draw.actorId;
  out.model = draw.model;
  const BlobTree* tree = drawTree(draw, project);
  if (!tree || countPoints(tree->root, minParticles) < minParticles) return out;
  TreeParticles tp = treeParticles(*tree, draw.treeTimeSec);
  out.centres = std::move(tp.set.position);
  out.radii = std::move(tp.set.radius);
  return out;
}

std::vector<ParticleDraw> ParticleView::takeMoving(SceneFrame& frame, const Project& project, double nowSec,
                                                   const ParticleViewSettings& settings) {
  pending_ = false;
  std::vector<ParticleDraw> out;
  if (!settings.enabled) {
    seen_.clear();
    return out;
  }
  std::map<std::string, Seen> seen;
  std::vector<BlobDraw> kept;
  for (BlobDraw& d : frame.blobs) {
    const BlobTree* tree = drawTree(d, project);
    if (!tree || countPoints(tree->root, settings.minParticles) < settings.minParticles) {
      kept.push_back(std::move(d));
      continue;
    }
    auto it = seen_.find(d.actorId);
    Seen s = it != seen_.end() ? it->second : Seen{};
    const BlobTree* own = d.tree ? d.tree.get() : nullptr;
    const bool first = it == seen_.end();
    if (settings.holding || (!first && (s.treeTimeSec != d.treeTimeSec || s.tree != own))) {
      s.movedAt = nowSec;
      s.waiting = true;
    }
    s.treeTimeSec = d.treeTimeSec;
    s.tree = own;
    seen[d.actorId] = s;
    if (nowSec - s.movedAt < settings.holdSec) {
      out.push_back(particleDraw(d, project, settings.minParticles));
      pending_ = true;
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
