#include <catch2/catch.hpp>

#include "core/doc/document.h"

using namespace animorph;

namespace {
Project projectWithActor() {
  Project p;
  Actor a;
  a.id = "hero";
  a.name = "Hero";
  a.assetPath = "hero.glb";
  p.actors.push_back(a);
  return p;
}
}  // namespace

TEST_CASE("commands apply, undo and redo", "[doc]") {
  Document doc;
  doc.reset(projectWithActor(), "");
  REQUIRE_FALSE(doc.dirty());
  doc.execute(setActorField(doc.project(), "hero", &Actor::speed, 2.0, "Set speed"));
  CHECK(doc.project().actors[0].speed == 2.0);
  CHECK(doc.dirty());
  CHECK(doc.history().undoLabel() == "Set speed");
  REQUIRE(doc.undo());
  CHECK(doc.project().actors[0].speed == 1.0);
  CHECK_FALSE(doc.dirty());
  REQUIRE(doc.redo());
  CHECK(doc.project().actors[0].speed == 2.0);
  CHECK_FALSE(doc.redo());
}

TEST_CASE("a drag merges into one undo step", "[doc]") {
  Document doc;
  doc.reset(projectWithActor(), "");
  doc.beginDrag();
  for (int i = 1; i <= 10; ++i)
    doc.execute(setActorField(doc.project(), "hero", &Actor::timeOffsetSec, 0.1 * i, "Move offset", "offset"));
  doc.endDrag();
  CHECK(doc.history().size() == 1);
  CHECK(doc.project().actors[0].timeOffsetSec == Approx(1.0));
  doc.undo();
  CHECK(doc.project().actors[0].timeOffsetSec == 0.0);
  doc.redo();
  CHECK(doc.project().actors[0].timeOffsetSec == Approx(1.0));
}

TEST_CASE("commands outside a drag do not merge, different keys do not merge", "[doc]") {
  Document doc;
  doc.reset(projectWithActor(), "");
  doc.execute(setActorField(doc.project(), "hero", &Actor::speed, 2.0, "s", "k"));
  doc.execute(setActorField(doc.project(), "hero", &Actor::speed, 3.0, "s", "k"));
  CHECK(doc.history().size() == 2);
  doc.beginDrag();
  doc.execute(setActorField(doc.project(), "hero", &Actor::speed, 4.0, "s", "a"));
  doc.execute(setActorField(doc.project(), "hero", &Actor::loop, false, "l", "b"));
  doc.endDrag();
  CHECK(doc.history().size() == 4);
}

TEST_CASE("a new edit after undo drops the redo history and the clean mark", "[doc]") {
  Document doc;
  doc.reset(projectWithActor(), "");
  doc.execute(setActorField(doc.project(), "hero", &Actor::speed, 2.0, "a"));
  doc.history().markClean();
  doc.undo();
  CHECK(doc.dirty());
  doc.execute(setActorField(doc.project(), "hero", &Actor::speed, 5.0, "b"));
  CHECK_FALSE(doc.history().canRedo());
  doc.undo();
  CHECK(doc.dirty());  // the saved state (speed 2) is unreachable now
}

TEST_CASE("structural commands add and remove actors", "[doc]") {
  Document doc;
  doc.reset(projectWithActor(), "");
  Actor b;
  b.id = doc.project().uniqueActorId("hero");
  CHECK(b.id == "hero_2");
  doc.execute(std::make_unique<LambdaCommand>(
      "Add actor", [b](Project& p) { p.actors.push_back(b); },
      [id = b.id](Project& p) { std::erase_if(p.actors, [&](const Actor& a) { return a.id == id; }); }));
  CHECK(doc.project().actors.size() == 2);
  doc.undo();
  CHECK(doc.project().actors.size() == 1);
}

TEST_CASE("the current frame is view state, not an edit", "[doc]") {
  Document doc;
  doc.setCurrentFrame(42);
  CHECK(doc.project().timeline.currentFrame == 42);
  CHECK_FALSE(doc.dirty());
  CHECK_FALSE(doc.history().canUndo());
}
