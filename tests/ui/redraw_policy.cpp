#include <catch2/catch.hpp>

#include "ui/shell/redraw_policy.h"

using namespace animorph;

TEST_CASE("the editor redraws on demand: at once while animating, a few frames after input, then waits",
          "[redraw]") {
  RedrawPolicy p;
  RedrawState idle;
  // Start-up settles like input.
  for (int i = 0; i < RedrawPolicy::kSettleFrames; ++i) CHECK(p.waitAfterFrame(idle) == 0.0);
  CHECK(p.waitAfterFrame(idle) == RedrawPolicy::kIdleTickSec);
  CHECK(p.waitAfterFrame(idle) == RedrawPolicy::kIdleTickSec);

  // An event: that frame and kSettleFrames more are drawn at once.
  RedrawState input;
  input.input = true;
  CHECK(p.waitAfterFrame(input) == 0.0);
  for (int i = 1; i < RedrawPolicy::kSettleFrames; ++i) CHECK(p.waitAfterFrame(idle) == 0.0);
  CHECK(p.waitAfterFrame(idle) == RedrawPolicy::kIdleTickSec);

  // Playback, a busy preview or a held button: never waits, however long.
  RedrawState anim;
  anim.animating = true;
  for (int i = 0; i < 100; ++i) CHECK(p.waitAfterFrame(anim) == 0.0);
  // ... and when it stops, the editor goes idle without settle frames of its own.
  CHECK(p.waitAfterFrame(idle) == RedrawPolicy::kIdleTickSec);

  // Input while animating still settles after the animation ends.
  anim.input = true;
  CHECK(p.waitAfterFrame(anim) == 0.0);
  anim.input = false;
  CHECK(p.waitAfterFrame(anim) == 0.0);
  int settled = 0;
  while (p.waitAfterFrame(idle) == 0.0) ++settled;
  CHECK(settled == RedrawPolicy::kSettleFrames);

  // A text field with the keyboard: the caret blinks, so idle frames come faster.
  RedrawState text;
  text.textInput = true;
  CHECK(p.waitAfterFrame(text) == RedrawPolicy::kCaretTickSec);
  CHECK(RedrawPolicy::kCaretTickSec < RedrawPolicy::kIdleTickSec);
}
