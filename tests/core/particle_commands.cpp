#include <catch2/catch.hpp>

#include "demo/statue.h"
#include "core/doc/blobtree_commands.h"
#include "core/doc/document.h"
#include "core/doc/particle_commands.h"

using namespace animorph;

namespace {

// A project holding the statue as the BlobTree actor "statue".
Project statueProject() {
  Project p;
  Actor a = makeBlobTreeActor(p, "statue");
  a.blobTree = makeStatue();
  p.actors.push_back(a);
  return p;
}

}  // namespace

TEST_CASE("particles: Convert and Simulate are one undo step each", "[particles][commands]") {
  Document d;
  d.reset(statueProject(), "");
  const BlobTree original = d.project().actors[0].blobTree;
  auto tree = [&] { return d.project().findActor("statue")->blobTree; };

  ConvertToParticlesSettings cs;
  cs.count = 500;
  ConvertToParticlesReport crep;
  auto convert = convertToParticlesCommand(d.project(), "statue", 0.0, cs, &crep);
  REQUIRE(convert);
  d.execute(std::move(*convert));
  CHECK(tree().root.children.size() == crep.particles);
  const BlobTree particles = tree();

  ParticleSettings s;
  s.durationSec = 1.0;
  s.forces.explosion.centre = glm::vec3(0.0f, 1.0f, 0.0f);
  auto sim = simulateParticlesCommand(d.project(), "statue", s, {});
  REQUIRE(sim);
  d.execute(std::move(*sim));
  const BlobTree simulated = tree();
  CHECK_FALSE(simulated == particles);
  CHECK(simulated.root.children[0].vec3Param("center").keys().size() > 1);

  REQUIRE(d.undo());
  CHECK(tree() == particles);
  REQUIRE(d.undo());
  CHECK(tree() == original);
  REQUIRE(d.redo());
  REQUIRE(d.redo());
  CHECK(tree() == simulated);

  auto bad = simulateParticlesCommand(d.project(), "nobody", s, {});
  REQUIRE_FALSE(bad);
  CHECK(bad.error().find("nobody") != std::string::npos);
  std::atomic<bool> cancel{true};
  s.cancel = &cancel;
  auto cancelled = simulateParticlesCommand(d.project(), "statue", s, {});
  REQUIRE_FALSE(cancelled);
  CHECK(cancelled.error().find("cancelled") != std::string::npos);
}

TEST_CASE("particles: Explode and re-form is one undo step and refuses bad targets", "[particles][commands]") {
  Document d;
  Project p = statueProject();
  Actor sphere = makeBlobTreeActor(p, "ball");  // a blend of one sphere at the origin
  p.actors.push_back(sphere);
  d.reset(p, "");
  ConvertToParticlesSettings cs;
  cs.count = 300;
  auto convert = convertToParticlesCommand(d.project(), "statue", 0.0, cs);
  REQUIRE(convert);
  d.execute(std::move(*convert));
  const Project before = d.project();

  ParticleSettings s;
  s.durationSec = 0.5;
  s.rateHz = 60.0;
  const ParticleAnimorphosisSettings as = reformSettings(s, ParticleBakeOptions{});
  auto self = particleReformCommand(d.project(), "statue", as, "statue");
  REQUIRE_FALSE(self);
  CHECK(self.error().find("itself") != std::string::npos);
  auto missing = particleReformCommand(d.project(), "statue", as, "nobody");
  REQUIRE_FALSE(missing);
  CHECK(missing.error().find("nobody") != std::string::npos);

  ParticleReformReport rep;
  auto reform = particleReformCommand(d.project(), "statue", as, "ball", &rep);
  INFO((reform ? std::string() : reform.error()));
  REQUIRE(reform);
  CHECK(rep.reformed);
  d.execute(std::move(*reform));
  const Project& q = d.project();
  REQUIRE(q.actors.size() == 3);
  CHECK(q.animorphosis.sourceActorId == "statue");
  CHECK(q.animorphosis.targetActorId == q.actors.back().id);
  CHECK(q.animorphosis.graph.links.size() == rep.particles);
  CHECK(rep.endSec == Approx(0.5));
  d.undo();
  CHECK(d.project() == before);
  d.redo();
  CHECK(d.project().actors.size() == 3);
}
