#include "core/doc/particle_commands.h"

#include "core/blobtree/compile.h"
#include "core/project/animorphosis_project.h"
#include "core/doc/blobtree_commands.h"
#include "core/particles/character_shape.h"
#include "core/particles/mesh_inside.h"
#include "core/project/actor_time.h"
#include "core/standin/fit_standin.h"

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

const char* particleSourceName(ParticleSource s) { return s == ParticleSource::Mesh ? "mesh" : "standin"; }

bool particleSourceFromName(const std::string& name, ParticleSource& out) {
  for (ParticleSource s : {ParticleSource::Standin, ParticleSource::Mesh})
    if (name == particleSourceName(s)) {
      out = s;
      return true;
    }
  return false;
}

Result<Actor> characterParticlesActor(const Project& p, const std::string& actorId, const Character& character,
                                      double timeSec, ParticleSource from, const ConvertToParticlesSettings& settings,
                                      CharacterParticlesReport* report) {
  const Actor* a = p.findActor(actorId);
  if (!a || a->kind != ActorKind::Gltf) return Error{"no glTF character actor '" + actorId + "'"};
  const std::string where = "actor '" + actorId + "' (" + a->assetPath + "): ";
  const AnimationClip* clip =
      a->clip >= 0 && a->clip < int(character.clips.size()) ? &character.clips[size_t(a->clip)] : nullptr;
  const float clipTime = clip ? float(actorClipTimeSec(*a, *clip, timeSec)) : 0.0f;
  CharacterParticlesReport rep;
  Result<ConvertToParticlesResult> conv = Error{"not run"};
  if (from == ParticleSource::Standin) {
    const ActorMorph* am = p.morph.findActor(actorId);
    Standin standin;
    if (am && !am->standin.segments.empty()) {
      standin = am->standin;
    } else {
      FitSettings fs;
      fs.measure = false;
      auto fit = fitStandin(character, fs);
      if (!fit) return Error{where + "no stand-in, and fitting one failed: " + fit.error()};
      standin = std::move(fit->standin);
      rep.standinFitted = true;
    }
    if (standin.segments.empty()) return Error{where + "the stand-in has no segment"};
    conv = convertToParticles(posedStandinProgram(character, standin, clip, clipTime), settings);
  } else {
    const MeshInside mesh(posedCharacterMesh(character, clip, clipTime));
    rep.triangles = mesh.info().triangles;
    rep.boundaryEdges = mesh.info().boundaryEdges;
    rep.meshVolume = mesh.info().volume;
    auto shape = meshParticleShape(mesh);
    if (!shape) return Error{where + shape.error()};
    conv = convertToParticles(*shape, settings);
    if (!conv && !mesh.closed())
      conv = Error{conv.error() + " (the mesh is not closed: " + std::to_string(mesh.info().boundaryEdges) +
                   " boundary edges)"};
  }
  if (!conv) return Error{where + conv.error()};
  if (conv->report.cancelled) return Error{where + "conversion cancelled"};
  rep.convert = conv->report;
  Actor out = makeBlobTreeActor(p, a->name + " particles");
  out.blobTree = std::move(conv->tree);
  out.transform = a->transform;
  out.loop = false;
  if (report) *report = rep;
  return out;
}

ParticleAnimorphosisSettings reformSettings(const ParticleSettings& settings, const ParticleBakeOptions& bake) {
  ParticleAnimorphosisSettings as;
  as.explosion = settings;
  as.vortex = settings;
  as.vortex.forces.explosion.enabled = false;
  as.vortex.forces.vortex.enabled = true;
  as.vortex.forces.gravity = glm::vec3(0.0f);
  as.startSec = bake.startSec;
  as.tolerance = bake.tolerance;
  as.quantum = bake.quantum;
  return as;
}

Result<ParticleReformEdit> particleReformEdit(const Project& p, const std::string& actorId,
                                              const ParticleAnimorphosisSettings& settings,
                                              const std::string& reformInto, ParticleReformReport* report) {
  auto a = blobActor(p, actorId);
  if (!a) return Error{a.error()};
  const Actor& actor = **a;
  ParticleAnimorphosisSettings as = settings;
  ParticleReformReport rep;
  const std::atomic<bool>* cancel = settings.explosion.cancel;
  auto cancelled = [&] { return Error{"actor '" + actorId + "': explode and re-form cancelled"}; };
  if (!reformInto.empty()) {  // B gathers into another actor's shape (in the trees' own spaces)
    if (reformInto == actorId) return Error{"actor '" + actorId + "': cannot re-form into itself"};
    auto shape = blobActor(p, reformInto);
    if (!shape) return Error{"re-form into: " + shape.error()};
    ConvertToParticlesSettings places;
    places.cancel = cancel;
    ParticleTransportSettings transport;
    transport.cancel = cancel;
    auto rest = reformIntoShape(actor.blobTree, settings.startSec,
                                compileFieldProgram((*shape)->blobTree, settings.startSec), places, transport,
                                &rep.transport);
    if (cancel && cancel->load()) return cancelled();
    if (!rest) return Error{"actor '" + reformInto + "': " + rest.error()};
    as.gatheringRest = std::move(*rest);
    rep.reformed = true;
  }
  auto pa = makeParticleAnimorphosis(actor.blobTree, as);
  if (!pa) return Error{"actor '" + actorId + "': " + pa.error()};
  if (pa->cancelled) return cancelled();
  ParticleReformEdit e;
  e.actorId = actorId;
  e.exploding = std::move(pa->exploding);
  e.gathering = makeBlobTreeActor(p, actor.name + " gathering");
  e.gathering.blobTree = std::move(pa->gathering);
  e.gathering.loop = false;
  e.gathering.transform = actor.transform;
  e.animorphosis.sourceActorId = actorId;
  e.animorphosis.targetActorId = e.gathering.id;
  e.animorphosis.startSec = pa->startSec;
  e.animorphosis.endSec = pa->endSec;
  e.animorphosis.graph = std::move(pa->graph);
  rep.particles = pa->explosionReport.particles;
  rep.keys = pa->explosionReport.keys + pa->vortexReport.keys;
  rep.maxError = std::max(pa->explosionReport.maxError, pa->vortexReport.maxError);
  rep.startSec = pa->startSec;
  rep.endSec = pa->endSec;
  Project trial = p;
  applyParticleReform(trial, e);
  if (Status st = checkAnimorphosis(trial); !st) return Error{"internal: " + st.error()};
  if (report) *report = rep;
  return e;
}

void applyParticleReform(Project& p, const ParticleReformEdit& edit) {
  if (Actor* a = p.findActor(edit.actorId)) {
    a->blobTree = edit.exploding;
    a->loop = false;
  }
  p.actors.push_back(edit.gathering);
  p.animorphosis = edit.animorphosis;
}

Result<std::unique_ptr<Command>> particleReformCommand(const Project& p, const std::string& actorId,
                                                       const ParticleAnimorphosisSettings& settings,
                                                       const std::string& reformInto, ParticleReformReport* report) {
  auto e = particleReformEdit(p, actorId, settings, reformInto, report);
  if (!e) return Error{e.error()};
  const Actor* before = p.findActor(actorId);
  auto edit = std::make_shared<const ParticleReformEdit>(std::move(*e));
  auto tree = std::make_shared<const BlobTree>(before->blobTree);
  const bool loop = before->loop;
  const AnimorphosisSetup setup = p.animorphosis;
  return std::unique_ptr<Command>(std::make_unique<LambdaCommand>(
      "Explode and re-form " + before->name, [edit](Project& q) { applyParticleReform(q, *edit); },
      [edit, tree, loop, setup](Project& q) {
        if (Actor* a = q.findActor(edit->actorId)) {
          a->blobTree = *tree;
          a->loop = loop;
        }
        std::erase_if(q.actors, [&](const Actor& a) { return a.id == edit->gathering.id; });
        q.animorphosis = setup;
      }));
}

}  // namespace animorph
