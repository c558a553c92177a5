#pragma once
// The frame loop's clock: seconds since start-up, the time between frames, and the smoothed frame
// time the status bar shows. A frame that follows a wait for input is not smoothed in: the previous
// frame's rendering finished during the wait, so its time says nothing of the frame rate.
#include <chrono>

namespace animorph {

class FrameClock {
 public:
  using Clock = std::chrono::steady_clock;

  // The first frame counts from here (not from start-up).
  void startFrames() { prev_ = Clock::now(); }
  // A new frame: dtSec since the previous one (or the wake).
  void tick() {
    now_ = Clock::now();
    dtSec_ = std::chrono::duration<double>(now_ - prev_).count();
    prev_ = now_;
    if (!wokeFromWait_) smoothedMs_ = 0.9 * smoothedMs_ + 0.1 * dtSec_ * 1000.0;
    wokeFromWait_ = false;
  }
  // The loop waited for input: the next frame counts from now, not from the last frame.
  void woke() {
    prev_ = Clock::now();
    wokeFromWait_ = true;
  }
  double nowSec() const { return std::chrono::duration<double>(now_ - start_).count(); }
  double sinceStartMs() const { return std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }
  double dtSec() const { return dtSec_; }
  double smoothedMs() const { return smoothedMs_; }
  // CLOCK_MONOTONIC seconds at the last tick (the GUI tests compare their own clock with it).
  double tickEpochSec() const { return std::chrono::duration<double>(now_.time_since_epoch()).count(); }

 private:
  Clock::time_point start_ = Clock::now(), prev_ = start_, now_ = start_;
  double dtSec_ = 0.0, smoothedMs_ = 16.0;
  bool wokeFromWait_ = false;
};

}  // namespace animorph
