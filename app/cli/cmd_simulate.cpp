// animorph-cli simulate P --actor ID -o P2 [options]: runs the particle system on a
// BlobTree actor's point primitives and bakes it into their tracks (docs/particles.md).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "core/blobtree/compile.h"
#include "app/cli/cli_command.h"
#include "core/project/asset_cache.h"
#include "core/doc/particle_commands.h"
#include "core/project/project_io.h"
#include "core/particles/convert_to_particles.h"

namespace {

using namespace animorph;
const char* kCmd = "simulate";

bool parseFloat(const std::string& s, float& out) {
  char* end = nullptr;
  out = std::strtof(s.c_str(), &end);
  return end && *end == '\0' && !s.empty();
}

bool parseVec3(const std::string& s, glm::vec3& out) {
  return std::sscanf(s.c_str(), "%f,%f,%f", &out.x, &out.y, &out.z) == 3;
}

struct SimulateArgs {
  std::string path, output, actorId, reformInto;
  int convert = 0;
  std::string from;  // a character actor's: standin or mesh
  bool animorphosis = false, vortexOnly = false;
  bool centreGiven = false;
  ParticleSettings s;
  ParticleBakeOptions bake;
};

// Reads the options into a; returns 0, or the exit code after printing the reason.
int parseSimulateArgs(const std::vector<std::string>& args, SimulateArgs& o) {
  ParticleSettings& s = o.s;
  // Float options and where they go.
  std::map<std::string, float*> floats = {
      {"--energy", &s.forces.explosion.energy}, {"--falloff", &s.forces.explosion.falloff},
      {"--drag", &s.forces.drag},               {"--restitution", &s.forces.restitution},
      {"--friction", &s.forces.friction},       {"--noise", &s.forces.noise},
      {"--ground", &s.forces.groundHeight},     {"--tolerance", &o.bake.tolerance},
      {"--swirl", &s.forces.vortex.swirl},      {"--vortex-radius", &s.forces.vortex.radius},
      {"--inward", &s.forces.vortex.inward},    {"--lift", &s.forces.vortex.lift},
      {"--coupling", &s.forces.vortex.coupling}};
  std::map<std::string, glm::vec3*> vectors = {{"--centre", &s.forces.explosion.centre},
                                              {"--gravity", &s.forces.gravity},
                                              {"--vortex-centre", &s.forces.vortex.centre},
                                              {"--axis", &s.forces.vortex.axis}};
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    bool takesValue = floats.count(a) || vectors.count(a) || a == "-o" || a == "--actor" || a == "--convert" ||
                      a == "--seed" || a == "--duration" || a == "--rate" || a == "--start" || a == "--reform-into" ||
                      a == "--from";
    if (takesValue && i + 1 >= args.size()) return cli::fail(kCmd, a + " needs a value", 2);
    if (a == "-o") o.output = args[++i];
    else if (a == "--actor") o.actorId = args[++i];
    else if (a == "--reform-into") o.reformInto = args[++i];
    else if (a == "--convert") o.convert = std::atoi(args[++i].c_str());
    else if (a == "--from") o.from = args[++i];
    else if (a == "--seed") s.seed = std::strtoull(args[++i].c_str(), nullptr, 10);
    else if (a == "--duration") s.durationSec = std::atof(args[++i].c_str());
    else if (a == "--rate") s.rateHz = std::atof(args[++i].c_str());
    else if (a == "--start") o.bake.startSec = std::atof(args[++i].c_str());
    else if (a == "--no-ground") s.forces.ground = false;
    else if (a == "--no-explosion") s.forces.explosion.enabled = false;
    else if (a == "--vortex") s.forces.vortex.enabled = true;
    else if (a == "--vortex-only") o.vortexOnly = true;
    else if (a == "--animorphosis") o.animorphosis = true;
    else if (floats.count(a)) {
      if (!parseFloat(args[++i], *floats[a])) return cli::fail(kCmd, a + ": not a number: " + args[i], 2);
    } else if (vectors.count(a)) {
      o.centreGiven |= a == "--centre";
      if (!parseVec3(args[++i], *vectors[a])) return cli::fail(kCmd, a + ": expected x,y,z, got " + args[i], 2);
    } else if (!a.empty() && a[0] == '-') return cli::fail(kCmd, "unknown option " + a, 2);
    else if (o.path.empty()) o.path = a;
    else return cli::fail(kCmd, "expected one project", 2);
  }
  if (!o.reformInto.empty() && !o.animorphosis) return cli::fail(kCmd, "--reform-into needs --animorphosis", 2);
  if (o.path.empty() || o.output.empty() || o.actorId.empty())
    return cli::fail(kCmd, "usage: simulate PROJECT.animorph --actor ID -o OUT.animorph [options]", 2);
  if (o.vortexOnly) {
    s.forces.explosion.enabled = false;
    s.forces.vortex.enabled = true;
  }
  return 0;
}

// A character actor: its stand-in or posed mesh becomes a new BlobTree actor of the project, which
// is the one simulated (o.actorId and actor follow it). Returns 0, or the exit code.
int convertCharacter(SimulateArgs& o, ParticleSource source, Project& p, Actor*& actor) {
  const std::string& path = o.path;
  if (o.convert <= 0) return cli::fail(kCmd, path + ": actor '" + o.actorId + "' is a character: give --convert N");
  const std::string asset = (std::filesystem::path(path).parent_path() / actor->assetPath).lexically_normal().string();
  AssetCache::Entry e = AssetCache::load(asset);
  if (!e.character) return cli::fail(kCmd, path + ": actor '" + o.actorId + "': " + asset + ": " + e.error);
  ConvertToParticlesSettings cs;
  cs.count = o.convert;
  CharacterParticlesReport rep;
  auto made = characterParticlesActor(p, o.actorId, *e.character, o.bake.startSec, source, cs, &rep);
  if (!made) return cli::fail(kCmd, path + ": " + made.error());
  std::printf("converted the %s of '%s' into actor '%s': %zu particles (spacing %.4g m, volume %.4g m^3, "
              "particles %.4g m^3)%s\n",
              source == ParticleSource::Mesh ? "mesh" : "stand-in", o.actorId.c_str(), made->id.c_str(),
              rep.convert.particles, rep.convert.spacing, rep.convert.shapeVolume, rep.convert.particleVolume,
              rep.standinFitted ? "; no stand-in: one was fitted" : "");
  if (source == ParticleSource::Mesh)
    std::printf("mesh: %zu triangles, %zu boundary edges%s, volume %.4g m^3\n", rep.triangles, rep.boundaryEdges,
                rep.boundaryEdges ? " (not closed: filled where 2 of 3 rays are inside)" : " (closed)", rep.meshVolume);
  o.actorId = made->id;
  p.actors.push_back(std::move(*made));
  actor = &p.actors.back();
  o.convert = 0;
  return 0;
}

// --animorphosis: the particles' explosion and re-forming as an animorphosis; else the simulation
// baked into the actor's tracks. Returns 0, or the exit code.
int simulateOrReform(const SimulateArgs& o, Project& p, Actor& actor) {
  const std::string& path = o.path;
  if (o.animorphosis) {
    ParticleReformReport rep;
    auto e = particleReformEdit(p, o.actorId, reformSettings(o.s, o.bake), o.reformInto, &rep);
    if (!e) return cli::fail(kCmd, path + ": " + e.error());
    if (rep.reformed)
      std::printf("re-forms into '%s': sum of squared paths %.4g m^2 (greedy start %.4g), %zu exchanges in %d sweeps\n",
                  o.reformInto.c_str(), rep.transport.cost, rep.transport.greedyCost, rep.transport.exchanges,
                  rep.transport.sweeps);
    applyParticleReform(p, *e);
    std::printf("animorphosis '%s' -> '%s' over %g..%g s: %zu particles, %zu keys, largest error %.3g m\n",
                o.actorId.c_str(), e->gathering.id.c_str(), rep.startSec, rep.endSec, rep.particles, rep.keys,
                double(rep.maxError));
    return 0;
  }
  auto r = simulateTreeParticles(actor.blobTree, o.s, o.bake);
  if (!r) return cli::fail(kCmd, path + ": actor '" + o.actorId + "': " + r.error());
  std::printf("simulated %zu particles, %d steps at %g Hz: %zu keys (%.1f a particle), largest error %.3g m; "
              "explosion momentum %.4g kg m/s, energy %.4g J\n",
              r->particles, r->steps, o.s.rateHz, r->keys, double(r->keys) / double(std::max<size_t>(1, r->particles)),
              r->maxError, glm::length(r->impulse.momentum), r->impulse.energy);
  return 0;
}

int runSimulate(const std::vector<std::string>& args) {
  SimulateArgs o;
  if (int rc = parseSimulateArgs(args, o)) return rc;
  const std::string& path = o.path;
  auto p = loadProject(path);
  if (!p) return cli::fail(kCmd, p.error());
  ParticleSource source = ParticleSource::Standin;
  if (!o.from.empty() && !particleSourceFromName(o.from, source))
    return cli::fail(kCmd, "--from: expected standin or mesh, got " + o.from, 2);
  Actor* actor = p->findActor(o.actorId);
  auto t0 = std::chrono::steady_clock::now();
  if (actor && actor->kind == ActorKind::Gltf) {
    if (int rc = convertCharacter(o, source, *p, actor)) return rc;
  } else if (!o.from.empty()) {
    return cli::fail(kCmd, "--from applies to a character actor only", 2);
  }
  if (!actor || actor->kind != ActorKind::BlobTree)
    return cli::fail(kCmd, path + ": no BlobTree or character actor '" + o.actorId + "'");
  if (o.convert > 0) {
    ConvertToParticlesSettings cs;
    cs.count = o.convert;
    auto conv = convertToParticles(compileFieldProgram(actor->blobTree, o.bake.startSec), cs);
    if (!conv) return cli::fail(kCmd, path + ": actor '" + o.actorId + "': " + conv.error());
    actor->blobTree = conv->tree;
    std::printf("converted actor '%s' into %zu particles (spacing %.4g m, volume %.4g m^3, particles %.4g m^3)\n",
                o.actorId.c_str(), conv->report.particles, conv->report.spacing, conv->report.shapeVolume,
                conv->report.particleVolume);
  }
  if (!o.centreGiven && o.s.forces.explosion.enabled) {
    // Default centre: the particles' centroid at the start.
    TreeParticles tp = treeParticles(actor->blobTree, o.bake.startSec);
    glm::dvec3 c(0.0);
    for (const auto& q : tp.set.position) c += glm::dvec3(q);
    if (!tp.set.position.empty()) o.s.forces.explosion.centre = glm::vec3(c / double(tp.set.position.size()));
  }
  if (int rc = simulateOrReform(o, *p, *actor)) return rc;
  if (auto st = saveProject(*p, o.output); !st) return cli::fail(kCmd, st.error());
  double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("wrote %s in %.2f s\n", o.output.c_str(), sec);
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("simulate", "simulate particles on a BlobTree actor and bake them into its tracks",
                     "usage: animorph-cli simulate PROJECT.animorph --actor ID -o OUT.animorph [options]\n"
                     "  Every point primitive of the actor's tree is a particle. Runs the particle\n"
                     "  system (deterministic for a seed, fixed step) from their positions and bakes\n"
                     "  the trajectories into their centre tracks (thinned within --tolerance).\n"
                     "  --convert N         first fill the actor's shape with about N particles; on a\n"
                     "                      character actor: a new BlobTree actor \"NAME particles\" is\n"
                     "                      made (the character stays) and simulated\n"
                     "  --from standin|mesh a character's stand-in (default; fitted when it has none)\n"
                     "                      or its skinned mesh, posed at --start\n"
                     "  --animorphosis      explosion A(t) and a time-reversed vortex B(t) of the same\n"
                     "                      particles (B a new actor), linked one to one, as the\n"
                     "                      project's animorphosis: the shape explodes and re-forms\n"
                     "  --reform-into ID2   with --animorphosis: B gathers into actor ID2's shape\n"
                     "                      (particles assigned to its volume so paths do not cross)\n"
                     "  --seed S --duration SEC (3) --rate HZ (120) --start SEC (0) --tolerance M (0.002)\n"
                     "  explosion: --centre x,y,z (centroid) --energy J (20) --falloff M (1) --no-explosion\n"
                     "  --gravity x,y,z (0,-9.81,0) --drag D (0.2) --noise A (0)\n"
                     "  ground: --ground Y (0) --restitution R (0.4) --friction F (0.2) --no-ground\n"
                     "  vortex: --vortex --vortex-only --vortex-centre x,y,z --axis x,y,z --swirl V (4)\n"
                     "          --vortex-radius M (0.5) --inward V (0.5) --lift V (0.8) --coupling C (2)\n",
                     runSimulate);
