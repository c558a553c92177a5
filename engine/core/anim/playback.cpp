#include "core/anim/playback.h"

#include <algorithm>
#include <cmath>

namespace animorph {
namespace {
constexpr double kFrameTolerance = 1e-6;

double safeFps(const Timeline& tl) { return tl.fps > 0.0 && std::isfinite(tl.fps) ? tl.fps : 24.0; }
int lastFrame(const Timeline& tl) { return std::max(tl.frameStart, tl.frameEnd); }
}  // namespace

double rangeStartSec(const Timeline& tl) { return tl.frameStart / safeFps(tl); }
double rangeEndSec(const Timeline& tl) { return (lastFrame(tl) + 1) / safeFps(tl); }

int Playback::frame(const Timeline& tl) const {
  int f = static_cast<int>(std::floor(timeSec_ * safeFps(tl) + kFrameTolerance));
  return std::clamp(f, tl.frameStart, lastFrame(tl));
}

void Playback::seekFrame(int frame, const Timeline& tl) {
  frame = std::clamp(frame, tl.frameStart, lastFrame(tl));
  timeSec_ = frame / safeFps(tl);
  compensation_ = 0.0;
}

void Playback::play(const Timeline& tl) {
  int f = std::clamp(tl.currentFrame, tl.frameStart, lastFrame(tl));
  double speed = tl.playbackSpeed;
  // A stopped playhead at the end of a non-looping range restarts from the
  // other end, as in every DCC application.
  if (!tl.loop && speed >= 0.0 && f == lastFrame(tl)) f = tl.frameStart;
  if (!tl.loop && speed < 0.0 && f == tl.frameStart) f = lastFrame(tl);
  // Keep the sub-frame part when the playhead already shows that frame, so
  // pause/play does not jump back to the frame start.
  if (frame(tl) != f) seekFrame(f, tl);
  playing_ = true;
}

void Playback::toggle(const Timeline& tl) {
  if (playing_) pause();
  else play(tl);
}

int Playback::advance(double dtSec, const Timeline& tl) {
  if (!playing_ || !(dtSec > 0.0) || !std::isfinite(dtSec)) return frame(tl);
  double step = dtSec * tl.playbackSpeed;
  if (!std::isfinite(step)) return frame(tl);
  // Kahan summation: the sum of 10^5 steps of 1/60 s stays exact to ~1e-15 s.
  double y = step - compensation_;
  double t = timeSec_ + y;
  compensation_ = (t - timeSec_) - y;
  timeSec_ = t;
  wrapOrClamp(tl);
  return frame(tl);
}

void Playback::wrapOrClamp(const Timeline& tl) {
  double start = rangeStartSec(tl), end = rangeEndSec(tl);
  double length = end - start;
  if (timeSec_ >= start && timeSec_ < end) return;
  if (tl.loop && length > 0.0) {
    double wrapped = start + std::fmod(timeSec_ - start, length);
    if (wrapped < start) wrapped += length;
    if (wrapped >= end) wrapped = start;  // fmod rounding at the exact end
    timeSec_ = wrapped;
    compensation_ = 0.0;
    return;
  }
  // Not looping: stop on the last (or, playing backwards, the first) frame.
  timeSec_ = timeSec_ >= end ? lastFrame(tl) / safeFps(tl) : start;
  compensation_ = 0.0;
  playing_ = false;
}

}  // namespace animorph
