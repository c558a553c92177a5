#include <catch2/catch.hpp>

#include <cmath>

#include "core/blobtree/compile.h"
#include "core/particles/particle_system.h"
#include "core/particles/particle_tree.h"
#include "core/particles/trajectory_bake.h"

using namespace animorph;

namespace {

// n particles in a 1 m cube standing on the ground, from a fixed generator.
ParticleSet cubeOfParticles(size_t n) {
  ParticleSet s;
  for (size_t i = 0; i < n; ++i) {
    glm::vec3 u(hashSigned(99, i, 0, 0), hashSigned(99, i, 0, 1), hashSigned(99, i, 0, 2));
    s.position.push_back(glm::vec3(0.5f * u.x, 0.6f + 0.5f * u.y, 0.5f * u.z));
    s.radius.push_back(0.02f);
  }
  return s;
}

BlobTree treeOf(const ParticleSet& s) {
  BlobTree t;
  t.root = makeBlobNode(NodeType::Blend, 1, "particles");
  for (size_t i = 0; i < s.size(); ++i) {
    BlobNode p = makeBlobNode(NodeType::Point, int(i) + 2);
    p.vec3Param("center") = Vec3Track(s.position[i]);
    p.floatParam("radius") = FloatTrack(0.05f);
    p.floatParam("intensity") = FloatTrack(1.5f);
    t.root.children.push_back(p);
  }
  return t;
}

ParticleSettings busySettings() {
  ParticleSettings s;
  s.durationSec = 1.5;
  s.forces.explosion.centre = glm::vec3(0.1f, 0.3f, 0.0f);
  s.forces.explosion.energy = 5.0f;
  s.forces.vortex.enabled = true;
  s.forces.vortex.centre = glm::vec3(0.0f);
  s.forces.noise = 3.0f;
  s.seed = 7;
  return s;
}

}  // namespace

TEST_CASE("particles: the same seed gives bit-identical tracks whatever the thread count", "[particles]") {
  BlobTree base = treeOf(cubeOfParticles(400));
  ParticleSettings s = busySettings();
  BlobTree a = base, b = base, c = base;
  s.threads = 1;
  REQUIRE(simulateTreeParticles(a, s, {}));
  s.threads = 0;
  REQUIRE(simulateTreeParticles(b, s, {}));
  s.threads = 3;
  REQUIRE(simulateTreeParticles(c, s, {}));
  CHECK(a == b);
  CHECK(a == c);
  CHECK_FALSE(a == base);
  BlobTree d = base;
  s.seed = 8;  // the noise differs
  REQUIRE(simulateTreeParticles(d, s, {}));
  CHECK_FALSE(a == d);
}

TEST_CASE("particles: momentum and energy after the explosion match the impulse", "[particles]") {
  ParticleSet set = cubeOfParticles(2000);
  for (size_t i = 0; i < set.size(); ++i) set.mass.push_back(0.5f + 0.5f * std::abs(hashSigned(3, i, 0, 0)));
  ParticleSettings s;
  s.forces.gravity = glm::vec3(0.0f);
  s.forces.drag = 0.0f;
  s.forces.ground = false;
  s.forces.explosion.centre = glm::vec3(0.3f, 0.2f, -0.1f);  // off centre: a net push
  s.forces.explosion.energy = 40.0f;
  s.forces.explosion.falloff = 0.4f;
  s.durationSec = 0.25;
  auto sim = ParticleSimulation::create(set, s);
  REQUIRE(sim);
  std::vector<glm::vec3> p, v;
  REQUIRE(sim->run(p, v));
  glm::dvec3 momentum(0.0);
  double kinetic = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    momentum += double(set.mass[i]) * glm::dvec3(v[i]);
    kinetic += 0.5 * set.mass[i] * glm::dot(glm::dvec3(v[i]), glm::dvec3(v[i]));
  }
  const ImpulseReport& j = sim->impulse();
  REQUIRE(glm::length(j.momentum) > 0.05 * j.magnitude);  // the test means something
  CHECK(glm::length(momentum - j.momentum) <= 0.01 * glm::length(j.momentum));
  CHECK(kinetic == Approx(40.0).epsilon(0.01));  // the energy asked for
  CHECK(j.energy == Approx(40.0).epsilon(0.01));
  // Points move away from the centre.
  size_t outward = 0;
  for (size_t i = 0; i < v.size(); ++i) outward += glm::dot(v[i], set.position[i] - glm::vec3(0.3f, 0.2f, -0.1f)) > 0;
  CHECK(outward == v.size());
  // Gravity alone changes the momentum by M g t.
  s.forces.gravity = glm::vec3(0.0f, -9.81f, 0.0f);
  auto fall = ParticleSimulation::create(set, s);
  REQUIRE(fall->run(p, v));
  double mass = 0.0, vy = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    mass += set.mass[i];
    vy += set.mass[i] * double(v[i].y);
  }
  CHECK(vy - j.momentum.y == Approx(-9.81 * mass * 0.25).epsilon(0.01));
}

TEST_CASE("particles: particles stay above the ground", "[particles]") {
  ParticleSet set = cubeOfParticles(800);
  ParticleSettings s = busySettings();
  s.forces.explosion.centre = glm::vec3(0.0f, 1.5f, 0.0f);  // above: everything is thrown down
  s.forces.explosion.energy = 30.0f;
  s.forces.vortex.lift = -1.0f;
  s.durationSec = 3.0;
  auto sim = ParticleSimulation::create(set, s);
  REQUIRE(sim);
  std::atomic<int> below{0}, bounced{0};
  REQUIRE(sim->forEachTrajectory([&](size_t i, const std::vector<glm::vec3>& path) {
    bool touched = false;
    for (const glm::vec3& p : path) {
      if (p.y < set.radius[i] - 1e-6f) ++below;
      touched |= p.y <= set.radius[i] + 1e-6f;
    }
    bounced += touched;
  }));
  CHECK(below == 0);
  CHECK(bounced > 400);  // most of them hit the ground
}

TEST_CASE("particles: baked tracks reproduce the simulation within the tolerance, thinned", "[particles]") {
  ParticleSet set = cubeOfParticles(300);
  BlobTree tree = treeOf(set);
  ParticleSettings s = busySettings();
  s.forces.vortex.enabled = false;
  s.forces.noise = 0.0f;
  s.durationSec = 2.0;
  ParticleBakeOptions o;
  o.startSec = 0.5;
  o.tolerance = 2e-3f;
  auto rep = simulateTreeParticles(tree, s, o);
  REQUIRE(rep);
  CHECK(rep->maxError <= o.tolerance);
  // Independently: run the simulation again and compare with every step.
  TreeParticles fresh = treeParticles(treeOf(set), 0.0);
  auto sim = ParticleSimulation::create(fresh.set, s);
  REQUIRE(sim);
  std::vector<std::vector<glm::vec3>> paths(set.size());
  REQUIRE(sim->forEachTrajectory([&](size_t i, const std::vector<glm::vec3>& p) { paths[i] = p; }));
  float worst = 0.0f;
  for (size_t i = 0; i < set.size(); ++i) {
    const Vec3Track& t = tree.root.children[i].vec3Param("center");
    for (size_t k = 0; k < paths[i].size(); ++k)
      worst = std::max(worst, glm::length(t.evaluate(o.startSec + double(k) / s.rateHz) - paths[i][k]));
  }
  CHECK(worst <= o.tolerance);
  size_t samples = set.size() * (size_t(sim->steps()) + 1);
  CHECK(rep->keys * 4 < samples);  // ballistic flights need few keys
  // Rounded keys (shorter files) keep the tolerance.
  BlobTree rounded = treeOf(set);
  o.quantum = 1e-4;
  auto repRounded = simulateTreeParticles(rounded, s, o);
  REQUIRE(repRounded);
  CHECK(repRounded->maxError <= o.tolerance);
  const Vec3Track& r5 = rounded.root.children[5].vec3Param("center");
  CHECK(r5.keys()[1].value.x == Approx(std::round(r5.keys()[1].value.x / 1e-4f) * 1e-4f).margin(1e-7));
  o.quantum = 0.0;
  // Reversed: the last step at the start.
  BlobTree back = treeOf(set);
  o.reverse = true;
  // Reverse sampling reads positions at the end of the run, i.e. the rest positions of this tree.
  REQUIRE(simulateTreeParticles(back, s, o));
  const Vec3Track& t0 = back.root.children[5].vec3Param("center");
  CHECK(glm::length(t0.evaluate(o.startSec + 2.0) - set.position[5]) <= 1e-5f);
  CHECK(glm::length(t0.evaluate(o.startSec) - paths[5].back()) <= o.tolerance);
}

TEST_CASE("particles: bad settings are refused with the reason", "[particles]") {
  BlobTree tree = treeOf(cubeOfParticles(10));
  ParticleSettings s;
  s.rateHz = 0.0;
  auto r = simulateTreeParticles(tree, s, {});
  REQUIRE_FALSE(r);
  CHECK(r.error().find("rate") != std::string::npos);
  s = ParticleSettings{};
  s.forces.restitution = 2.0f;
  CHECK_FALSE(simulateTreeParticles(tree, s, {}));
  BlobTree empty;
  auto e = simulateTreeParticles(empty, ParticleSettings{}, {});
  REQUIRE_FALSE(e);
  CHECK(e.error().find("no point primitive") != std::string::npos);
}
