#include <catch2/catch.hpp>

#include <algorithm>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

namespace {
// The hero -> other morph scene: neither actor has a weight map yet.
void addMorph(EditorFixture& f) { f.loadHeroMorphScene(); }

const std::vector<float>* heroMap(EditorHarness& h) {
  const ActorMorph* am = h.doc().project().morph.findActor("hero");
  return am ? &am->weightMap : nullptr;
}
}  // namespace

TEST_CASE("P enters Weight Paint mode on the morph's source and shows the tool panel", "[paint]") {
  EditorFixture f;
  addMorph(f);
  auto& h = f.h;
  CHECK_FALSE(h.hasWidget("paint/panel"));
  h.tapKey(GLFW_KEY_P);
  h.frames(1);
  CHECK(h.ui->state().paint.active);
  CHECK(h.doc().selection.actorId == "hero");
  CHECK(h.hasWidget("paint/panel"));
  CHECK(h.hasWidget("paint/radius"));
  CHECK(h.hasWidget("viewport/paint_note"));
  REQUIRE(h.hasWidget("paint/target"));
  CHECK(h.ui->output().weightPaintMode);
  CHECK(h.ui->output().weightOverlay.actorId == "hero");
  // ] grows the brush, [ shrinks it.
  const float r0 = h.ui->state().paint.brush.radiusPx;
  h.moveTo(h.widgetCenter("paint/target"));
  h.tapKey(GLFW_KEY_RIGHT_BRACKET);
  CHECK(h.ui->state().paint.brush.radiusPx > r0);
  h.tapKey(GLFW_KEY_LEFT_BRACKET);
  CHECK(h.ui->state().paint.brush.radiusPx == Approx(r0));
  h.tapKey(GLFW_KEY_P);
  CHECK_FALSE(h.ui->state().paint.active);
}

TEST_CASE("a paint stroke updates the map live and is one undo step", "[paint]") {
  EditorFixture f;
  addMorph(f);
  auto& h = f.h;
  h.tapKey(GLFW_KEY_P);
  h.frames(1);
  h.ui->state().camera.target = {0.0f, 1.0f, 0.0f};  // the hero's middle at the viewport's centre, clear of the panel
  h.ui->state().camera.distanceM = 7.0f;
  h.frames(1);
  h.ui->state().paint.brush.radiusPx = 150.0f;
  h.ui->state().paint.brush.strength = 0.5f;
  REQUIRE(h.hasWidget("paint/target"));
  auto target = *h.ui->widgets().find("paint/target");
  auto panel = *h.ui->widgets().find("paint/panel");
  INFO("target " << target.min.x << "," << target.min.y << " - " << target.max.x << "," << target.max.y << "; panel "
                 << panel.min.x << "," << panel.min.y << " - " << panel.max.x << "," << panel.max.y);
  REQUIRE(heroMap(h) == nullptr);

  h.settle();
  h.moveTo({target.min.x, target.center().y});
  h.press(0);
  h.moveTo(target.center());
  // Mid-stroke: the overlay shows paint, the document has not changed yet.
  const auto& live = h.ui->output().weightOverlay.weights;
  REQUIRE(live.size() == 4);
  CHECK(*std::max_element(live.begin(), live.end()) > 0.0f);
  CHECK(h.doc().history().size() == 0);
  h.moveTo({target.max.x, target.center().y});
  h.release(0);
  h.frames(1);

  CHECK(h.doc().history().size() == 1);
  REQUIRE(heroMap(h) != nullptr);
  const std::vector<float> painted = *heroMap(h);
  REQUIRE(painted.size() == 4);
  CHECK(*std::max_element(painted.begin(), painted.end()) > 0.0f);
  CHECK(h.doc().selection.actorId == "hero");  // the click did not pick or clear the selection

  h.tapKey(GLFW_KEY_Z, true);
  CHECK(heroMap(h) == nullptr);  // undo removes the map (and the entry) exactly
  CHECK_FALSE(h.doc().dirty());
  h.tapKey(GLFW_KEY_Z, true, true);
  REQUIRE(heroMap(h) != nullptr);
  CHECK(*heroMap(h) == painted);

  // Fill and Clear are one step each.
  h.clickWidget("paint/fill");
  CHECK(*heroMap(h) == std::vector<float>(4, 0.5f));
  h.clickWidget("paint/clear");
  CHECK(heroMap(h)->empty());
  CHECK(h.doc().history().size() == 3);
}

TEST_CASE("importing weights from a character without vertex colours reports the file", "[paint]") {
  EditorFixture f;
  addMorph(f);
  auto& h = f.h;
  h.tapKey(GLFW_KEY_P);
  h.frames(1);
  h.clickWidget("paint/import");
  CHECK(h.ui->state().status.error);
  CHECK(h.ui->state().status.text.find("hero.gltf: no vertex colours (COLOR_0)") != std::string::npos);
  CHECK(h.doc().history().size() == 0);
}

TEST_CASE("importing weights from the texture of a character without one reports the file", "[paint]") {
  EditorFixture f;
  addMorph(f);
  auto& h = f.h;
  h.tapKey(GLFW_KEY_P);
  h.frames(1);
  h.clickWidget("paint/import_texture");
  CHECK(h.ui->state().status.error);
  CHECK(h.ui->state().status.text.find("hero.gltf: no mesh has texture coordinates and a decoded base colour texture") !=
        std::string::npos);
  CHECK(h.doc().history().size() == 0);
}
