#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "ui/inspector/inspector_panel.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

namespace {
void addPlainActor(EditorHarness& h) {
  Project p;
  Actor a;
  a.id = "box";
  a.name = "Box";
  p.actors.push_back(a);
  h.document->reset(p, "");
  h.document->selection = {"box", -1};
  h.frames(2);
}
}  // namespace

TEST_CASE("an inspector drag is one undo step and Ctrl+Z restores the value", "[inspector]") {
  EditorFixture f;
  auto& h = f.h;
  addPlainActor(h);
  REQUIRE(h.hasWidget("inspector/offset"));
  glm::vec2 c = h.widgetCenter("inspector/offset");
  h.drag(c, c + glm::vec2(120.0f, 0.0f), 0, 12);
  const Actor& a = h.doc().project().actors[0];
  CHECK(a.timeOffsetSec > 0.2);
  CHECK(h.doc().history().size() == 1);
  CHECK(h.doc().history().undoLabel() == "Set time offset of Box");
  CHECK(h.doc().dirty());
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().actors[0].timeOffsetSec == 0.0);
  CHECK_FALSE(h.doc().dirty());
  h.tapKey(GLFW_KEY_Z, true, true);  // Ctrl+Shift+Z redoes
  CHECK(h.doc().project().actors[0].timeOffsetSec > 0.2);
  h.tapKey(GLFW_KEY_Z, true);
  h.tapKey(GLFW_KEY_Y, true);  // Ctrl+Y redoes too
  CHECK(h.doc().project().actors[0].timeOffsetSec > 0.2);
}

TEST_CASE("dragging the translation X field moves the actor in one undo step", "[inspector]") {
  EditorFixture f;
  auto& h = f.h;
  addPlainActor(h);
  auto r = *h.ui->widgets().find("inspector/translate");
  glm::vec2 x{r.min.x + 12.0f, r.center().y};  // the first of the three fields
  h.drag(x, x + glm::vec2(-80.0f, 0.0f), 0, 8);
  glm::vec3 t = h.doc().project().actors[0].transform.translation;
  CHECK(t.x < -0.2f);
  CHECK(t.y == 0.0f);
  CHECK(t.z == 0.0f);
  CHECK(h.doc().history().size() == 1);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().actors[0].transform.translation == glm::vec3(0.0f));
  // Two separate drags are two steps.
  h.drag(x, x + glm::vec2(30.0f, 0.0f), 0, 4);
  h.drag(x, x + glm::vec2(30.0f, 0.0f), 0, 4);
  CHECK(h.doc().history().index() == 2);
}

TEST_CASE("Euler degrees convert to the stored quaternion and back", "[inspector]") {
  for (glm::vec3 deg : {glm::vec3(10, 20, 30), glm::vec3(-45, 80, 170), glm::vec3(0, 0, 0), glm::vec3(90, 0, -90)}) {
    glm::quat q = eulerDegToQuat(deg);
    glm::vec3 back = quatToEulerDeg(q);
    glm::quat q2 = eulerDegToQuat(back);
    CHECK(std::abs(glm::dot(q, q2)) == Approx(1.0f).margin(1e-5));  // same rotation
  }
  // X rotation of 90 degrees turns +Y into +Z.
  glm::vec3 y = eulerDegToQuat({90, 0, 0}) * glm::vec3(0, 1, 0);
  CHECK(y.z == Approx(1.0f).margin(1e-5));
}

TEST_CASE("renaming in the inspector is a command, typing does not trigger shortcuts", "[inspector]") {
  EditorFixture f;
  auto& h = f.h;
  addPlainActor(h);
  h.clickWidget("inspector/name");
  h.tapKey(GLFW_KEY_A, true);
  h.type("Crate 2");
  h.tapKey(GLFW_KEY_SPACE);  // a text field has focus: no play/pause
  CHECK_FALSE(h.ui->state().playback.playing());
  h.tapKey(GLFW_KEY_ENTER);
  CHECK(h.doc().project().actors[0].name == "Crate 2");
  CHECK(h.doc().project().actors[0].id == "box");
  CHECK(h.doc().history().size() == 1);
}
