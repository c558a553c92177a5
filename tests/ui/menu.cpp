#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

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
