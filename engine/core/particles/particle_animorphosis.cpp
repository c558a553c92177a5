#include "core/particles/particle_animorphosis.h"

namespace animorph {

namespace {

void collectPoints(const BlobNode& n, CorrespondenceGraph& g) {
  if (n.type == NodeType::Point) {
    CorrespondenceLink l;
    l.nodeA = l.nodeB = n.id;
    g.links.push_back(l);
  }
  for (const BlobNode& c : n.children) collectPoints(c, g);
}

}  // namespace

CorrespondenceGraph identityPointLinks(const BlobTree& tree) {
  CorrespondenceGraph g;
  collectPoints(tree.root, g);
  return g;
}

Result<ParticleAnimorphosis> makeParticleAnimorphosis(const BlobTree& particles,
                                                      const ParticleAnimorphosisSettings& s) {
  ParticleAnimorphosis out;
  out.exploding = particles;
  out.gathering = s.gatheringRest ? *s.gatheringRest : particles;
  if (identityPointLinks(out.gathering).links.size() != identityPointLinks(particles).links.size())
    return Error{"gathering: the re-formed tree does not have the particles' points"};
  ParticleBakeOptions o;
  o.startSec = s.startSec;
  o.tolerance = s.tolerance;
  o.quantum = s.quantum;
  auto a = simulateTreeParticles(out.exploding, s.explosion, o);
  if (!a) return Error{"explosion: " + a.error()};
  if (a->cancelled) {
    out.cancelled = true;
    return out;
  }
  ParticleSettings vortex = s.vortex;
  vortex.durationSec = s.explosion.durationSec;
  vortex.rateHz = s.explosion.rateHz;
  o.reverse = true;
  auto b = simulateTreeParticles(out.gathering, vortex, o);
  if (!b) return Error{"vortex: " + b.error()};
  out.cancelled = b->cancelled;
  out.explosionReport = *a;
  out.vortexReport = *b;
  out.graph = identityPointLinks(particles);
  out.startSec = s.startSec;
  out.endSec = s.startSec + double(a->steps) / s.explosion.rateHz;
  return out;
}

}  // namespace animorph
