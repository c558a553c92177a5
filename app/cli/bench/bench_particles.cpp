// animorph-cli bench particles: the particle system (simulation, baking into
// tracks), Convert to particles (of the statue's field and of its polygonised mesh), and the 128^3 CPU polygonisation of 40,000
// small primitives against the smooth statue they fill (same run).
#include <chrono>
#include <cstdio>
#include <string>

#include "core/blobtree/compile.h"
#include "app/cli/bench/bench.h"
#include "demo/statue.h"
#include "core/particles/convert_to_particles.h"
#include "core/particles/mesh_inside.h"
#include "core/particles/particle_tree.h"
#include "core/poly/polygonizer.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

double secondsOf(const std::function<void()>& fn) {
  auto a = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

std::vector<Row> benchParticles(const bench::Options& opt) {
  std::vector<Row> rows;
  const int count = opt.quick ? 4000 : 40000;
  const double duration = opt.quick ? 1.0 : 5.0;
  const std::string n = std::to_string(count);
  BlobTree statue = makeStatue();
  FieldProgram shape = compileFieldProgram(statue, 0.0);
  ConvertToParticlesSettings cs;
  cs.count = count;
  Result<ConvertToParticlesResult> conv = Error{""};
  double convertSec = secondsOf([&] { conv = convertToParticles(shape, cs); });
  if (!conv) {
    std::fprintf(stderr, "bench particles: %s\n", conv.error().c_str());
    return rows;
  }
  const BlobTree& particles = conv->tree;
  rows.push_back({"convert the statue to " + n + " particles", convertSec * 1e3, "ms", "",
                  std::to_string(conv->report.particles) + " particles, volume " +
                      std::to_string(conv->report.particleVolume) + " vs " + std::to_string(conv->report.shapeVolume)});
  // The statue's polygonised mesh (about 50k triangles) filled the same way: the mesh's inside test
  // against the field's, on the same lattices.
  PolygonizeSettings meshSettings;
  meshSettings.resolution = opt.quick ? 96 : 160;
  auto statueMesh = polygonize(shape, meshSettings);
  if (statueMesh) {
    Result<ConvertToParticlesResult> fromMesh = Error{""};
    double meshSec = secondsOf([&] {
      const MeshInside inside(statueMesh->mesh);
      auto meshShape = meshParticleShape(inside);
      if (meshShape) fromMesh = convertToParticles(*meshShape, cs);
    });
    if (fromMesh)
      rows.push_back({"  the same from its polygonised mesh", meshSec * 1e3, "ms", "",
                      std::to_string(statueMesh->mesh.triangleCount()) + " triangles, " +
                          std::to_string(fromMesh->report.particles) + " particles, volume " +
                          std::to_string(fromMesh->report.particleVolume)});
  }

  ParticleSettings s = statueDemoSettings({}).explosion;
  s.durationSec = duration;
  s.rateHz = 120.0;
  TreeParticles tp = treeParticles(particles, 0.0);
  auto sim = ParticleSimulation::create(tp.set, s);
  std::vector<glm::vec3> p, v;
  double simSec = secondsOf([&] { sim->run(p, v); });
  rows.push_back({"simulate " + n + " particles " + std::to_string(int(duration)) + " s at 120 Hz", simSec, "s",
                  opt.quick ? "" : "<= 10 s", std::to_string(sim->steps()) + " steps, all threads"});
  ParticleSettings one = s;
  one.threads = 1;
  auto sim1 = ParticleSimulation::create(tp.set, one);
  double oneSec = secondsOf([&] { sim1->run(p, v); });
  rows.push_back({"  baseline: the same on one thread", oneSec, "s", "", ""});
  BlobTree baked = particles;
  ParticleBakeReport rep;
  double bakeSec = secondsOf([&] { rep = *simulateTreeParticles(baked, s, {}); });
  rows.push_back({"simulate + bake into tracks", bakeSec, "s", "",
                  std::to_string(rep.keys) + " keys (" + std::to_string(rep.keys / std::max<size_t>(1, rep.particles)) +
                      " a particle) for " + std::to_string(rep.steps + 1) + " steps, error <= " +
                      std::to_string(rep.maxError) + " m"});

  PolygonizeSettings ps;
  ps.resolution = 128;
  FieldProgram program = compileFieldProgram(particles, 0.0);
  PolygonizeResult last;
  double ms = bench::medianMs(opt.quick ? 1 : 3, [&] { last = *polygonize(program, ps); });
  rows.push_back({"128^3 CPU polygonisation of " + n + " particles", ms, "ms", opt.quick ? "" : "<= 150 ms",
                  std::to_string(last.mesh.triangleCount()) + " tris, " +
                      std::to_string(last.stats.primitiveEvaluations / 1000000) + "M primitive candidates"});
  ps.subBlockListsForSkeletal = true;
  double msOld = bench::medianMs(opt.quick ? 1 : 3, [&] { last = *polygonize(program, ps); });
  rows.push_back({"  baseline: per-sub-block lists (before)", msOld, "ms", "",
                  std::to_string(last.stats.primitiveEvaluations / 1000000) + "M primitive candidates"});
  ps.subBlockListsForSkeletal = false;
  double msStatue = bench::medianMs(opt.quick ? 1 : 3, [&] { last = *polygonize(shape, ps); });
  rows.push_back({"  baseline: the smooth statue (8 primitives), 128^3", msStatue, "ms", "",
                  std::to_string(last.mesh.triangleCount()) + " tris"});
  return rows;
}

}  // namespace

ANIMORPH_BENCH("particles", "particle simulation, baking, convert to particles, polygonising 40,000 particles",
               benchParticles);
