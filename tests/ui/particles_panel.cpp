// The inspector's Particles section (ui/inspector/particles_panel.h): Convert to particles and Simulate run as
// background jobs (the harness finishes each frame's job) and are one undo step each.
#include <catch2/catch.hpp>

#include "inspector/particles_panel.h"
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
  CHECK(n >= 240);  // about the count: the lattice of a small count is coarse (341 for 300 here)
  CHECK(n <= 360);
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
