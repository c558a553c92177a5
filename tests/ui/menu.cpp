#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "core/doc/document.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

TEST_CASE("View menu toggles change ViewOptions through undoable commands", "[menu]") {
  EditorFixture f;
  auto& h = f.h;
  REQUIRE(h.doc().project().view.showGrid);
  h.clickWidget("menu/View");
  REQUIRE(h.hasWidget("menu/Grid"));
  h.clickWidget("menu/Grid");
  CHECK_FALSE(h.doc().project().view.showGrid);
  CHECK(h.doc().dirty());
  CHECK(h.doc().history().undoLabel() == "Toggle grid");
  h.clickWidget("menu/View");
  h.clickWidget("menu/Wireframe");
  CHECK(h.doc().project().view.wireframe);
  // Edit > Undo names what it undoes and undoes it.
  h.clickWidget("menu/Edit");
  REQUIRE(h.hasWidget("menu/Undo"));
  h.clickWidget("menu/Undo");
  CHECK_FALSE(h.doc().project().view.wireframe);
  CHECK_FALSE(h.doc().project().view.showGrid);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().view.showGrid);
  CHECK_FALSE(h.doc().dirty());
}

TEST_CASE("Help windows open from the menu and list the shortcut table", "[menu]") {
  EditorFixture f;
  auto& h = f.h;
  h.clickWidget("menu/Help");
  h.clickWidget("menu/Shortcuts");
  CHECK(h.ui->state().showShortcuts);
  h.frames(1);
  CHECK(h.hasWidget("shortcuts/table"));
  h.clickWidget("menu/View");
  h.clickWidget("menu/Preferences...");
  CHECK(h.ui->state().showPreferences);
}

TEST_CASE("Help > Demos lists the demo projects and opens the one chosen", "[menu]") {
  EditorFixture f;
  auto& h = f.h;
  h.frames(1);
  h.clickWidget("menu/Help");
  REQUIRE(h.hasWidget("menu/Demos"));  // there, disabled, with no demo folder
  h.clickWidget("menu/Help");          // closes the menu

  for (const char* name : {"walker.animorph", "blobs.animorph"}) {
    Document d;
    Project p;
    p.name = name;
    d.reset(p, f.dir.file(std::string("demos/") + name));
    std::filesystem::create_directories(f.dir.file("demos"));
    REQUIRE(d.save());
  }
  std::ofstream(f.dir.file("demos/notes.txt")) << "not a project";
  h.ui->setDemoDir(f.dir.file("demos"));
  REQUIRE(h.ui->state().demoProjects.size() == 2);
  CHECK(h.ui->state().demoProjects[0] == f.dir.file("demos/blobs.animorph"));  // sorted

  h.clickWidget("menu/Help");
  h.clickWidget("menu/Demos");
  REQUIRE(h.hasWidget("menu/Demos/walker"));
  h.clickWidget("menu/Demos/walker");
  h.frames(2);
  CHECK(h.doc().path() == f.dir.file("demos/walker.animorph"));
  CHECK(h.doc().project().name == "walker.animorph");
}
