// The inspector's Particles section (ui/inspector/particles_panel.h): Convert to particles and Simulate run as
// background jobs (the harness finishes each frame's job) and are one undo step each.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "ui/inspector/particles_panel.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

namespace {

const BlobNode* firstPoint(const BlobNode& n) {
  if (n.type == NodeType::Point) return &n;
  for (const BlobNode& c : n.children)
    if (const BlobNode* p = firstPoint(c)) return p;
  return nullptr;
}

// Presses Cancel in the job panel of the job just started (still running) and waits for it to end.
void cancelRunningJob(EditorHarness& h) {
  REQUIRE(h.ui->runningJob());
  h.frames(1);  // the job panel with its Cancel button
  REQUIRE(h.ui->runningJob());
  REQUIRE(h.hasWidget("job/cancel"));
  h.clickWidget("job/cancel");
  for (int i = 0; i < 3000 && h.ui->runningJob(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    h.frames(1);
  }
  REQUIRE_FALSE(h.ui->runningJob());
}

}  // namespace

TEST_CASE("the Particles section converts a BlobTree actor and simulates it, one undo step each", "[ui][particles]") {
  EditorFixture f({1600.0f, 1800.0f});  // tall: the whole section fits in the inspector
  auto& h = f.h;
  h.clickWidget("outliner/new_blob");
  const Actor* a = blobActor(h);
  REQUIRE(a);
  const std::string id = a->id;
  const BlobTree sphere = a->blobTree;
  h.frames(2);
  REQUIRE(h.hasWidget("inspector/particles/convert"));
  CHECK_FALSE(h.hasWidget("inspector/particles/simulate"));  // no particles yet
  const size_t steps = h.doc().history().size();

  auto& st = h.ui->state().inspector.particles;
  st.convertCount = 300;
  h.clickWidget("inspector/particles/convert");
  h.frames(2);
  INFO(h.ui->state().status.text);
  CHECK_FALSE(h.ui->state().status.error);
  CHECK_FALSE(h.ui->runningJob());
  const size_t n = countParticles(blobActor(h)->blobTree);
  CHECK(n >= 300);  // the count asked, within 1 % above
  CHECK(n <= 303);
  CHECK(h.doc().history().size() == steps + 1);
  REQUIRE(h.hasWidget("inspector/particles/simulate"));
  // The settings were set up for the new tree: the explosion at its centroid.
  CHECK(glm::length(st.settings.forces.explosion.centre - glm::vec3(0.0f)) < 0.3f);

  st.settings.durationSec = 1.0;
  st.settings.rateHz = 60.0;
  st.settings.forces.explosion.energy = 5.0f;
  h.clickWidget("inspector/particles/simulate");
  h.frames(2);
  CHECK_FALSE(h.ui->state().status.error);
  CHECK(h.ui->state().status.text.find("Simulate") == 0);
  CHECK(h.doc().history().size() == steps + 2);
  const BlobNode* p = firstPoint(blobActor(h)->blobTree.root);
  REQUIRE(p);
  const Vec3Track& centre = p->vec3Param("center");
  CHECK(centre.keys().size() >= 2);
  CHECK(glm::length(centre.evaluate(0.5) - centre.evaluate(0.0)) > 0.01f);
  CHECK(st.settings.forces.explosion.energy == 5.0f);  // kept for the next run

  h.doc().undo();
  h.frames(1);
  p = firstPoint(blobActor(h)->blobTree.root);
  REQUIRE(p);
  CHECK(p->vec3Param("center").keys().size() <= 1);  // at rest again
  h.doc().undo();
  h.frames(1);
  CHECK(blobActor(h)->blobTree == sphere);
}

namespace {

// A new BlobTree actor (a sphere) converted to count particles through the section; its id.
std::string convertedActor(EditorHarness& h, int count) {
  h.clickWidget("outliner/new_blob");
  h.frames(2);
  const std::string id = h.doc().selection.actorId;
  h.ui->state().inspector.particles.convertCount = count;
  h.clickWidget("inspector/particles/convert");
  h.frames(2);
  REQUIRE(countParticles(h.doc().project().findActor(id)->blobTree) >= size_t(count));
  return id;
}

}  // namespace

TEST_CASE("the Particles section explodes particles and re-forms them into another actor's shape", "[ui][particles]") {
  EditorFixture f({1600.0f, 2200.0f});
  auto& h = f.h;
  // The shape to re-form into: a second BlobTree actor (a sphere), moved away in its tree's space.
  h.clickWidget("outliner/new_blob");
  h.frames(2);
  const std::string target = h.doc().selection.actorId;
  {
    Project p = h.doc().project();
    BlobNode* sphere = &p.findActor(target)->blobTree.root;
    while (!sphere->children.empty()) sphere = &sphere->children.front();
    REQUIRE(sphere->vec3Param("center").keys().size() <= 1);
    sphere->vec3Param("center") = Vec3Track(glm::vec3(2.0f, 0.0f, 0.0f));
    h.doc().reset(p, f.dir.file("scene.animorph"));
    h.doc().selection = {target, -1};
    h.frames(2);
  }
  const std::string id = convertedActor(h, 400);
  const Project before = h.doc().project();
  const size_t steps = h.doc().history().size();
  REQUIRE(h.hasWidget("inspector/particles/reform_into"));
  h.clickWidget("inspector/particles/reform_into");
  h.frames(1);
  REQUIRE(h.hasWidget("inspector/particles/reform_into/" + target));
  CHECK_FALSE(h.hasWidget("inspector/particles/reform_into/" + id));  // not into itself
  h.clickWidget("inspector/particles/reform_into/" + target);
  h.frames(1);
  auto& st = h.ui->state().inspector.particles;
  CHECK(st.reformInto == target);
  st.settings.durationSec = 1.0;
  st.settings.rateHz = 60.0;
  h.clickWidget("inspector/particles/reform");
  h.frames(2);
  INFO(h.ui->state().status.text);
  CHECK_FALSE(h.ui->state().status.error);
  CHECK(h.ui->state().status.text.find("Explode and re-form") == 0);
  CHECK(h.doc().history().size() == steps + 1);
  const Project& p = h.doc().project();
  REQUIRE(p.actors.size() == before.actors.size() + 1);
  const Actor& gathering = p.actors.back();
  CHECK(p.animorphosis.sourceActorId == id);
  CHECK(p.animorphosis.targetActorId == gathering.id);
  const size_t n = countParticles(gathering.blobTree);
  CHECK(p.animorphosis.graph.links.size() == n);
  // B ends at rest inside the other shape: every particle near x = 2 at the end of the interval.
  TreeParticles end = treeParticles(gathering.blobTree, p.animorphosis.endSec);
  REQUIRE(end.set.position.size() == n);
  for (const glm::vec3& q : end.set.position) CHECK(glm::length(q - glm::vec3(2.0f, 0.0f, 0.0f)) < 1.05f);
  h.doc().undo();
  h.frames(1);
  CHECK(h.doc().project() == before);
}

TEST_CASE("cancelling Simulate in the Particles section leaves the particles as they were", "[ui][particles]") {
  EditorFixture f({1600.0f, 1800.0f});
  auto& h = f.h;
  const std::string id = convertedActor(h, 20000);
  const BlobTree before = h.doc().project().findActor(id)->blobTree;
  const size_t steps = h.doc().history().size();
  auto& st = h.ui->state().inspector.particles;
  st.settings.durationSec = 5.0;  // seconds of work: still running when Cancel is pressed
  h.finishJobs = false;
  h.clickWidget("inspector/particles/simulate");
  cancelRunningJob(h);
  INFO(h.ui->state().status.text);
  CHECK(h.ui->state().status.text.find("cancelled") != std::string::npos);
  CHECK(h.doc().history().size() == steps);
  CHECK(h.doc().project().findActor(id)->blobTree == before);
}

TEST_CASE("the Particles section converts a character's stand-in into a new particle actor, and refuses a flat mesh",
          "[ui][particles]") {
  EditorFixture f({1600.0f, 1800.0f});
  auto& h = f.h;
  f.loadHeroScene();  // the hero: a flat quad skinned to two bones, no stand-in
  h.doc().selection = {"hero", -1};
  h.frames(2);
  REQUIRE(h.hasWidget("inspector/particles/convert"));
  REQUIRE(h.hasWidget("inspector/particles/from_standin"));
  CHECK_FALSE(h.hasWidget("inspector/particles/simulate"));  // a character has no particles of its own
  const Project before = h.doc().project();
  const size_t steps = h.doc().history().size();
  auto& st = h.ui->state().inspector.particles;
  st.convertCount = 200;

  // Its mesh encloses nothing: a clear error, nothing changed.
  h.clickWidget("inspector/particles/from_mesh");
  CHECK(st.convertFrom == ParticleSource::Mesh);
  h.clickWidget("inspector/particles/convert");
  h.frames(2);
  CHECK(h.ui->state().status.error);
  CHECK(h.ui->state().status.text.find("actor 'hero'") != std::string::npos);
  CHECK(h.ui->state().status.text.find("flat") != std::string::npos);
  CHECK(h.doc().project() == before);
  CHECK(h.doc().history().size() == steps);
  REQUIRE(h.hasWidget("error/ok"));  // the error dialog, the editor still running
  h.clickWidget("error/ok");
  h.frames(1);

  // Its stand-in: none yet, one is fitted for the conversion (the actor keeps none).
  h.clickWidget("inspector/particles/from_standin");
  CHECK(st.convertFrom == ParticleSource::Standin);
  h.clickWidget("inspector/particles/convert");
  h.frames(2);
  INFO(h.ui->state().status.text);
  CHECK_FALSE(h.ui->state().status.error);
  CHECK(h.ui->state().status.text.find("from the stand-in") != std::string::npos);
  CHECK(h.ui->state().status.text.find("one was fitted") != std::string::npos);
  CHECK(h.doc().history().size() == steps + 1);
  REQUIRE(h.doc().project().actors.size() == 2);
  const Actor& made = h.doc().project().actors[1];
  CHECK(made.kind == ActorKind::BlobTree);
  CHECK(h.doc().selection.actorId == made.id);  // the new actor is selected
  const size_t n = countParticles(made.blobTree);
  CHECK(n >= 200);
  CHECK(n <= 202);
  CHECK(h.doc().project().actors[0] == before.actors[0]);  // the character is left as it is
  CHECK(h.doc().project().morph.actors.empty());
  h.frames(2);
  CHECK(h.hasWidget("inspector/particles/simulate"));  // the new actor's particles can be simulated
  h.doc().undo();
  h.frames(1);
  CHECK(h.doc().project() == before);
}

TEST_CASE("cancelling a character's Convert to particles adds no actor", "[ui][particles]") {
  EditorFixture f({1600.0f, 1800.0f});
  auto& h = f.h;
  f.loadHeroScene();
  h.doc().selection = {"hero", -1};
  h.frames(2);
  const Project before = h.doc().project();
  auto& st = h.ui->state().inspector.particles;
  st.convertCount = 1'000'000;  // seconds of work: still running when Cancel is pressed
  h.clickWidget("inspector/particles/from_standin");
  h.finishJobs = false;
  h.clickWidget("inspector/particles/convert");
  cancelRunningJob(h);
  INFO(h.ui->state().status.text);
  CHECK(h.ui->state().status.text.find("cancelled") != std::string::npos);
  CHECK(h.doc().project() == before);
  CHECK(h.doc().history().size() == 0);
}
