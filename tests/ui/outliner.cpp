#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

namespace {
// Clicks the expand arrow of a tree node (left of its label).
void expand(EditorHarness& h, const std::string& key) {
  auto r = *h.ui->widgets().find(key);
  h.click({r.min.x + 8.0f, r.center().y});
}
}  // namespace

TEST_CASE("outliner lists actors and their node hierarchy, clicks select", "[outliner]") {
  EditorFixture f;
  f.loadHeroScene();
  auto& h = f.h;
  REQUIRE(h.hasWidget("outliner/hero"));
  h.clickWidget("outliner/hero");
  CHECK(h.doc().selection == Selection{"hero", -1});
  CHECK_FALSE(h.hasWidget("outliner/hero/node/1"));
  expand(h, "outliner/hero");
  REQUIRE(h.hasWidget("outliner/hero/node/0"));  // Body (skinned mesh), a root
  REQUIRE(h.hasWidget("outliner/hero/node/1"));  // Armature
  expand(h, "outliner/hero/node/1");
  expand(h, "outliner/hero/node/2");
  REQUIRE(h.hasWidget("outliner/hero/node/3"));  // spine, under hip
  h.clickWidget("outliner/hero/node/3");
  CHECK(h.doc().selection == Selection{"hero", 3});
  CHECK_FALSE(h.doc().dirty());  // selection is view state
}

TEST_CASE("outliner shows asset load errors in place", "[outliner]") {
  EditorFixture f;
  auto& h = f.h;
  Project p;
  Actor a;
  a.id = "ghost";
  a.name = "ghost";
  a.assetPath = "missing.glb";
  p.actors.push_back(a);
  h.doc().reset(p, f.dir.file("scene.animorph"));
  h.frames(2);
  REQUIRE(h.hasWidget("outliner/ghost/error"));
  const auto& e = h.assets.get(h.doc().resolveAsset("missing.glb"));
  CHECK(e.character == nullptr);
  CHECK(e.error.find("missing.glb") != std::string::npos);
}

TEST_CASE("double-click renames, Del deletes, the box toggles visibility: all undoable", "[outliner]") {
  EditorFixture f;
  f.loadHeroScene();
  auto& h = f.h;
  h.doubleClick(h.widgetCenter("outliner/hero"));
  REQUIRE(h.hasWidget("outliner/hero/rename"));
  h.type("Villain");
  h.tapKey(GLFW_KEY_ENTER);
  CHECK(h.doc().project().actors[0].name == "Villain");
  CHECK(h.doc().history().undoLabel() == "Rename hero to Villain");

  h.clickWidget("outliner/hero/visible");
  CHECK_FALSE(h.doc().project().actors[0].visible);

  h.clickWidget("outliner/hero");
  h.tapKey(GLFW_KEY_DELETE);
  CHECK(h.doc().project().actors.empty());
  CHECK(h.doc().selection.actorId.empty());

  h.tapKey(GLFW_KEY_Z, true);
  REQUIRE(h.doc().project().actors.size() == 1);
  CHECK_FALSE(h.doc().project().actors[0].visible);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().actors[0].visible);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().actors[0].name == "hero");
  CHECK_FALSE(h.doc().dirty());
}

TEST_CASE("Import Character adds an actor with a project-relative path, undoable", "[outliner]") {
  EditorFixture f;
  f.loadHeroScene();
  auto& h = f.h;
  h.clickWidget("menu/File");
  h.clickWidget("menu/Import Character...");
  REQUIRE(h.ui->state().browser.isOpen());
  h.type(f.dir.file("hero.gltf"));
  h.tapKey(GLFW_KEY_ENTER);
  h.frames(1);
  REQUIRE(h.doc().project().actors.size() == 2);
  const Actor& added = h.doc().project().actors[1];
  CHECK(added.id == "hero_2");
  CHECK(added.assetPath == "hero.gltf");
  CHECK(h.doc().selection.actorId == "hero_2");
  CHECK(added.name == "hero 2");  // the scene's hero keeps its name, the second one is numbered
  CHECK(h.doc().history().undoLabel() == "Add hero 2");
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().actors.size() == 1);
}

TEST_CASE("files dropped on the window: glTF files are imported, a project opens, others are refused",
          "[outliner][drop]") {
  EditorFixture f;
  f.loadHeroScene();
  auto& h = f.h;
  // Two glTF files (one with an upper-case extension): two actors, each its own undo step.
  std::string upper = f.dir.file("HERO2.GLTF");
  writeTestCharacter(upper);
  h.ui->requestDrop({f.dir.file("hero.gltf"), upper});
  h.frames(1);
  REQUIRE(h.doc().project().actors.size() == 3);
  CHECK(h.doc().project().actors[2].assetPath == "HERO2.GLTF");
  CHECK(h.doc().selection.actorId == h.doc().project().actors[2].id);
  CHECK_FALSE(h.ui->state().status.error);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().actors.size() == 2);

  // Anything else: nothing changes, and the status bar names the file and says what can be dropped.
  h.ui->requestDrop({f.dir.file("notes.txt")});
  h.frames(1);
  CHECK(h.doc().project().actors.size() == 2);
  CHECK(h.ui->state().status.error);
  CHECK_THAT(h.ui->state().status.text, Catch::Contains("notes.txt") && Catch::Contains(".animorph"));

  // A project: the document is dirty, so the unsaved-changes prompt comes first; Don't Save opens it.
  Project other;
  Actor a;
  a.id = "villain";
  a.assetPath = "hero.gltf";
  other.actors.push_back(a);
  Document saved;
  saved.reset(other, f.dir.file("other.animorph"));
  REQUIRE(saved.save());
  h.ui->requestDrop({f.dir.file("hero.gltf"), f.dir.file("other.animorph")});
  h.frames(2);
  CHECK(h.ui->state().pending == PendingKind::OpenPath);
  REQUIRE(h.hasWidget("prompt/dont_save"));
  h.clickWidget("prompt/dont_save");
  h.frames(2);
  REQUIRE(h.doc().project().actors.size() == 1);
  CHECK(h.doc().project().actors[0].id == "villain");
  CHECK(h.doc().path() == f.dir.file("other.animorph"));
}
