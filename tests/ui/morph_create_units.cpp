// Create > Morph... aligns the target by its units (and asks before a resize no unit explains),
// in one undo step with the morph.
#include <catch2/catch.hpp>

#include "ui/inspector/morph_create.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// hero (the test character, metres) and "giant": the same rig with its roots scaled k times (as a
// file in centimetres would hold it for k = 100), declared in centimetres or in glTF's metres.
// glTF cannot declare centimetres, so giant is handed to the editor's asset cache as an importer
// would return it, not written.
void loadHeroAndGiant(EditorFixture& f, bool declared, float k = 100.0f) {
  Character hero = f.loadHeroScene();
  for (int r : hero.roots) hero.nodes[r].rest.scale *= k, hero.nodes[r].rest.translation *= k;
  if (declared) hero.unit = {0.01, "centimetres", true};
  const std::string asset = f.dir.file("giant.gltf");
  AssetCache::Entry giantEntry;
  giantEntry.character = std::make_shared<const Character>(hero);
  giantEntry.mtime = -1;  // what the cache records for a file that is not on disk: refresh() keeps it
  f.h.assets.insert(asset, giantEntry);
  Project p = f.h.doc().project();
  Actor giant = p.actors[0];
  giant.id = giant.name = "giant";
  giant.assetPath = "giant.gltf";
  p.actors.push_back(giant);
  f.h.document->reset(p, f.dir.file("scene.animorph"));
  f.h.frames(1);
  openCreateMorph(f.h.doc(), f.h.ui->state().createMorph);
  f.h.frames(3);
}

}  // namespace

TEST_CASE("Create > Morph...: a centimetre target is scaled by its unit with the morph, one undo step", "[morph][units]") {
  EditorFixture f;
  loadHeroAndGiant(f, true);
  auto& h = f.h;
  REQUIRE(h.hasWidget("morph/create/align"));
  CHECK_FALSE(h.hasWidget("morph/create/allow_resize"));
  h.clickWidget("morph/create/create");
  h.frames(2);
  const Project& p = h.doc().project();
  REQUIRE(p.morph.enabled());
  CHECK(p.findActor("giant")->transform.scale.x == Approx(0.01f));
  CHECK_THAT(h.ui->state().status.text, Catch::Contains("target in centimetres, scaled by 0.01 to the source's metres"));
  CHECK(h.doc().history().size() == 1);
  h.doc().undo();
  CHECK_FALSE(h.doc().project().morph.enabled());
  CHECK(h.doc().project().findActor("giant")->transform.scale.x == Approx(1.0f));
}

TEST_CASE("Create > Morph...: glTF holding centimetre numbers is scaled by 0.01 without asking, and says so",
          "[morph][units]") {
  EditorFixture f;
  loadHeroAndGiant(f, false);
  auto& h = f.h;
  REQUIRE(h.hasWidget("morph/create/align"));
  CHECK_FALSE(h.hasWidget("morph/create/allow_resize"));
  h.clickWidget("morph/create/create");
  h.frames(2);
  REQUIRE(h.doc().project().morph.enabled());
  CHECK(h.doc().project().findActor("giant")->transform.scale.x == Approx(0.01f));
  CHECK_THAT(h.ui->state().status.text, Catch::Contains("(probably authored in centimetres): scaled by 0.01"));
}

TEST_CASE("Create > Morph...: a 300x resize no unit explains needs the box ticked, unticking Align keeps the target",
          "[morph][units]") {
  EditorFixture f;
  loadHeroAndGiant(f, false, 300.0f);
  auto& h = f.h;
  REQUIRE(h.hasWidget("morph/create/allow_resize"));
  h.clickWidget("morph/create/create");
  h.frames(2);
  CHECK_FALSE(h.doc().project().morph.enabled());
  CHECK_THAT(h.ui->state().createMorph.error, Catch::Contains("which no unit explains"));
  h.clickWidget("morph/create/allow_resize");
  h.clickWidget("morph/create/create");
  h.frames(2);
  REQUIRE(h.doc().project().morph.enabled());
  CHECK(h.doc().project().findActor("giant")->transform.scale.x == Approx(1.0f / 300.0f).epsilon(1e-3));

  h.doc().undo();
  openCreateMorph(h.doc(), h.ui->state().createMorph);
  h.frames(3);
  h.clickWidget("morph/create/align");  // untick: the target stays as it is
  CHECK_FALSE(h.hasWidget("morph/create/allow_resize"));
  h.clickWidget("morph/create/create");
  h.frames(2);
  REQUIRE(h.doc().project().morph.enabled());
  CHECK(h.doc().project().findActor("giant")->transform.scale.x == Approx(1.0f));
}
