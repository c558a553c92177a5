#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "editor/selection_info.h"
#include "support/editor_fixture.h"
#include "ui/timeline/timeline_panel.h"

using namespace animorph;
using namespace animorph::test;

TEST_CASE("dragging on the timeline ruler scrubs the current frame", "[timeline]") {
  EditorFixture f;
  auto& h = f.h;
  REQUIRE(h.hasWidget("timeline/ruler"));
  auto r = *h.ui->widgets().find("timeline/ruler");
  float y = r.center().y;
  const TimelineState& tls = h.ui->state().timeline;
  auto frameAtX = [&](float x) {
    double pxPerFrame = (r.max.x - r.min.x) / (tls.viewEndFrame - tls.viewStartFrame);
    return static_cast<int>(std::lround(tls.viewStartFrame + (x - r.min.x) / pxPerFrame));
  };
  // Press at a quarter, drag to three quarters: the frame follows the mouse.
  float x0 = r.min.x + 0.25f * (r.max.x - r.min.x), x1 = r.min.x + 0.75f * (r.max.x - r.min.x);
  h.moveTo({x0, y});
  h.press();
  CHECK(h.doc().project().timeline.currentFrame == frameAtX(x0));
  int prev = h.doc().project().timeline.currentFrame;
  for (int i = 1; i <= 5; ++i) {
    h.moveTo({x0 + (x1 - x0) * i / 5.0f, y});
    CHECK(h.doc().project().timeline.currentFrame > prev);
    prev = h.doc().project().timeline.currentFrame;
  }
  h.release();
  CHECK(h.doc().project().timeline.currentFrame == frameAtX(x1));
  CHECK(frameAtX(x1) > 40);
  // Beyond the range end the frame clamps to it; scrubbing is not an edit.
  h.drag({x1, y}, {r.max.x - 1.0f, y});
  CHECK(h.doc().project().timeline.currentFrame == h.doc().project().timeline.frameEnd);
  CHECK_FALSE(h.doc().dirty());
  CHECK(h.doc().history().size() == 0);
}

TEST_CASE("Space toggles playback and frames advance with simulated time", "[timeline]") {
  EditorFixture f;
  auto& h = f.h;
  h.tapKey(GLFW_KEY_SPACE);
  REQUIRE(h.ui->state().playback.playing());
  int start = h.doc().project().timeline.currentFrame;
  h.frames(24, 1.0 / 24.0);  // one second at 24 fps
  CHECK(h.doc().project().timeline.currentFrame == start + 24);
  // A slow UI (10 fps) drops frames but keeps real time.
  h.frames(5, 0.1);
  CHECK(h.doc().project().timeline.currentFrame == start + 36);
  h.tapKey(GLFW_KEY_SPACE);
  CHECK_FALSE(h.ui->state().playback.playing());
  int paused = h.doc().project().timeline.currentFrame;
  h.frames(30);
  CHECK(h.doc().project().timeline.currentFrame == paused);
  // The Play button in the timeline does the same.
  h.clickWidget("timeline/play");
  CHECK(h.ui->state().playback.playing());
}

TEST_CASE("frame step and range shortcuts move the playhead", "[timeline]") {
  EditorFixture f;
  auto& h = f.h;
  const Timeline& tl = h.doc().project().timeline;
  h.tapKey(GLFW_KEY_END);
  CHECK(tl.currentFrame == tl.frameEnd);
  h.tapKey(GLFW_KEY_LEFT);
  CHECK(tl.currentFrame == tl.frameEnd - 1);
  h.tapKey(GLFW_KEY_HOME);
  CHECK(tl.currentFrame == tl.frameStart);
  h.tapKey(GLFW_KEY_RIGHT);
  h.tapKey(GLFW_KEY_RIGHT);
  CHECK(tl.currentFrame == tl.frameStart + 2);
  // Looping timeline: stepping back from the start wraps to the end.
  h.tapKey(GLFW_KEY_HOME);
  h.tapKey(GLFW_KEY_LEFT);
  CHECK(tl.currentFrame == tl.frameEnd);
}

TEST_CASE("range and fps fields are undoable project edits", "[timeline]") {
  EditorFixture f;
  auto& h = f.h;
  h.clickWidget("timeline/range_end");
  h.tapKey(GLFW_KEY_A, true);  // select all
  h.type("48");
  h.tapKey(GLFW_KEY_ENTER);
  CHECK(h.doc().project().timeline.frameEnd == 48);
  CHECK(h.doc().dirty());
  CHECK(h.doc().history().undoLabel() == "Set range end");
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().timeline.frameEnd == 96);
  h.clickWidget("timeline/loop");
  CHECK_FALSE(h.doc().project().timeline.loop);
}

TEST_CASE("ruler label spacing adapts to the zoom", "[timeline]") {
  CHECK(rulerLabelStep(60.0) == 1);
  CHECK(rulerLabelStep(30.0) == 2);
  CHECK(rulerLabelStep(12.0) == 5);
  CHECK(rulerLabelStep(6.0) == 10);
  CHECK(rulerLabelStep(0.5) == 100);
  CHECK(rulerLabelStep(0.01) == 5000);
  for (double ppf = 0.001; ppf < 200.0; ppf *= 1.37) {
    int step = rulerLabelStep(ppf);
    CHECK(step * ppf >= 50.0);  // labels never overlap
    if (step > 1) CHECK(step * ppf < 50.0 * 2.5 + 1e-9);  // and are not needlessly sparse
  }
}

TEST_CASE("key ticks are the selected actor's clip keys mapped through offset and speed", "[timeline]") {
  EditorFixture f;
  f.loadHeroScene();
  auto& h = f.h;
  CHECK(selectionKeyFrames(h.doc(), h.assets).empty());  // nothing selected
  h.doc().selection = {"hero", -1};
  // Keys at 0, 0.25, 0.5, 1.0 s of a 1 s looping clip, at 24 fps over 0..96.
  std::vector<int> expected;
  for (int cycle = 0; cycle <= 4; ++cycle)
    for (int k : {0, 6, 12})
      if (cycle * 24 + k <= 96) expected.push_back(cycle * 24 + k);
  CHECK(selectionKeyFrames(h.doc(), h.assets) == expected);

  // Offset 0.5 s, speed 2, not looping: keys at 0.5 + t/2 for t in the clip.
  h.doc().execute(setActorField(h.doc().project(), "hero", &Actor::timeOffsetSec, 0.5, "offset"));
  h.doc().execute(setActorField(h.doc().project(), "hero", &Actor::speed, 2.0, "speed"));
  h.doc().execute(setActorField(h.doc().project(), "hero", &Actor::loop, false, "loop"));
  CHECK(selectionKeyFrames(h.doc(), h.assets) == std::vector<int>{12, 15, 18, 24});

  // A selected joint shows only its own channel's keys (hip: 0 and 1 s).
  h.doc().selection = {"hero", 2};
  CHECK(selectionKeyFrames(h.doc(), h.assets) == std::vector<int>{12, 24});
}

TEST_CASE("a morph marker's flag on the ruler drags that marker, one undo step", "[timeline]") {
  EditorFixture f;
  f.loadHeroMorphScene();
  REQUIRE(f.h.hasWidget("timeline/marker/B"));
  const glm::vec2 a = f.h.widgetCenter("timeline/marker/A"), c = f.h.widgetCenter("timeline/marker/C");
  const float pxPerFrame = (c.x - a.x) / 20.0f;
  // The flag starts just right of the marker's line: press at its left edge (the marker goes to the mouse's frame).
  const WidgetRect flag = *f.h.ui->widgets().find("timeline/marker/B");
  const glm::vec2 b(flag.min.x + 1.0f, flag.center().y);
  const size_t steps = f.h.doc().history().index();
  f.h.drag(b, b + glm::vec2(5.0f * pxPerFrame, 0.0f), 0, 5);
  f.h.frames(1);
  CHECK(f.h.doc().project().morph.markers.b == 25);
  CHECK(f.h.doc().project().morph.markers.a == 10);
  CHECK(f.h.doc().history().index() == steps + 1);
  CHECK(f.h.doc().project().timeline.currentFrame == 0);  // the playhead stays
}
