#include <catch2/catch.hpp>

#include <cmath>

#include "core/anim/playback.h"

using namespace animorph;

namespace {
Timeline timeline(int start, int end, double fps, bool loop, double speed = 1.0) {
  Timeline tl;
  tl.frameStart = start;
  tl.frameEnd = end;
  tl.fps = fps;
  tl.loop = loop;
  tl.playbackSpeed = speed;
  tl.currentFrame = start;
  return tl;
}
}  // namespace

TEST_CASE("playback does not drift over 10,000 steps", "[playback]") {
  // 10,000 UI frames at 60 Hz are 166.67 s = exactly 4000 frames at 24 fps.
  Timeline tl = timeline(0, 100000, 24.0, false);
  Playback pb;
  pb.play(tl);
  int frame = 0;
  for (int i = 0; i < 10000; ++i) frame = pb.advance(1.0 / 60.0, tl);
  CHECK(frame == 4000);
  CHECK(pb.timeSec() == Approx(10000.0 / 60.0).epsilon(1e-14));
  // Uneven dt that sums to a whole number of seconds lands on the exact frame.
  Playback pb2;
  pb2.play(tl);
  for (int i = 0; i < 10000; ++i) frame = pb2.advance(i % 2 ? 0.013 : 0.007, tl);
  CHECK(frame == 2400);  // 10000 * 0.01 s = 100 s
  CHECK(std::abs(pb2.timeSec() - 100.0) < 1e-9);
}

TEST_CASE("playback drops frames when the UI is slow and honours speed", "[playback]") {
  Timeline tl = timeline(0, 1000, 24.0, false);
  Playback pb;
  pb.play(tl);
  CHECK(pb.advance(0.5, tl) == 12);  // one slow UI frame: 12 frames skipped, not 1 shown
  CHECK(pb.advance(1.0 / 24.0, tl) == 13);
  tl.playbackSpeed = 2.0;
  CHECK(pb.advance(0.5, tl) == 37);
  tl.playbackSpeed = 0.5;
  CHECK(pb.advance(1.0, tl) == 49);
}

TEST_CASE("playback loops over the range", "[playback]") {
  Timeline tl = timeline(10, 19, 10.0, true);  // 10 frames, 1 s
  Playback pb;
  pb.play(tl);
  CHECK(pb.frame(tl) == 10);
  CHECK(pb.advance(0.95, tl) == 19);  // last frame is shown for a full period
  CHECK(pb.advance(0.1, tl) == 10);   // wrapped
  CHECK(pb.playing());
  // Many wraps at once (a very long stall) still land on the right frame.
  CHECK(pb.advance(100.25, tl) == 13);  // 1.05 s + 100.25 s wraps to 1.30 s
  // Backwards playback wraps to the end.
  tl.playbackSpeed = -1.0;
  CHECK(pb.advance(0.35, tl) == 19);
}

TEST_CASE("playback stops at the end of a non-looping range", "[playback]") {
  Timeline tl = timeline(0, 9, 10.0, false);
  Playback pb;
  pb.play(tl);
  CHECK(pb.advance(5.0, tl) == 9);
  CHECK_FALSE(pb.playing());
  CHECK(pb.advance(1.0, tl) == 9);  // paused: no movement
  // Play again from the end restarts at the range start.
  tl.currentFrame = 9;
  pb.play(tl);
  CHECK(pb.frame(tl) == 0);
  CHECK(pb.playing());
}

TEST_CASE("playback ignores bad dt and seeks clamp to the range", "[playback]") {
  Timeline tl = timeline(5, 20, 24.0, true);
  Playback pb;
  pb.seekFrame(100, tl);
  CHECK(pb.frame(tl) == 20);
  pb.seekFrame(-3, tl);
  CHECK(pb.frame(tl) == 5);
  pb.play(tl);
  CHECK(pb.advance(-1.0, tl) == 5);
  CHECK(pb.advance(std::nan(""), tl) == 5);
  CHECK(pb.advance(INFINITY, tl) == 5);
  pb.toggle(tl);
  CHECK_FALSE(pb.playing());
  CHECK(pb.advance(1.0, tl) == 5);
}
