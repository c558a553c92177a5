#include "doc/particle_commands.h"

#include "blobtree/compile.h"
#include "doc/blobtree_commands.h"

namespace animorph {

namespace {

Result<const Actor*> blobActor(const Project& p, const std::string& actorId) {
  const Actor* a = p.findActor(actorId);
  if (!a || a->kind != ActorKind::BlobTree) return Error{"no BlobTree actor '" + actorId + "'"};
  return a;
}

}  // namespace

Result<std::unique_ptr<Command>> simulateParticlesCommand(const Project& p, const std::string& actorId,
                                                          const ParticleSettings& settings,
                                                          const ParticleBakeOptions& options,
                                                          ParticleBakeReport* report) {
  auto a = blobActor(p, actorId);
  if (!a) return Error{a.error()};
  BlobTree tree = (*a)->blobTree;
  auto r = simulateTreeParticles(tree, settings, options);
  if (!r) return Error{"actor '" + actorId + "': " + r.error()};
  if (r->cancelled) return Error{"actor '" + actorId + "': simulation cancelled"};
  if (report) *report = *r;
  return setBlobTreeCommand(p, actorId, std::move(tree), "Simulate particles");
}

Result<std::unique_ptr<Command>> convertToParticlesCommand(const Project& p, const std::string& actorId,
                                                           double timeSec, const ConvertToParticlesSettings& settings,
                                                           ConvertToParticlesReport* report) {
  auto a = blobActor(p, actorId);
  if (!a) return Error{a.error()};
  auto r = convertToParticles(compileFieldProgram((*a)->blobTree, timeSec), settings);
  if (!r) return Error{"actor '" + actorId + "': " + r.error()};
  if (r->report.cancelled) return Error{"actor '" + actorId + "': conversion cancelled"};
  if (report) *report = r->report;
  return setBlobTreeCommand(p, actorId, std::move(r->tree), "Convert to particles");
}

}  // namespace animorph
