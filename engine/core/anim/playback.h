#pragma once
// Real-time playback of the timeline: advances a time in seconds by the
// wall-clock time that passed, times the playback speed, and derives the
// current frame from it (frames are dropped when a UI frame takes longer
// than one timeline frame). Pure: no clock of its own, the caller passes dt.
#include "core/anim/timeline.h"

namespace animorph {

class Playback {
 public:
  // Starts playing from the timeline's current frame (or from the range
  // start when the current frame is at the end of a non-looping range).
  void play(const Timeline& tl);
  void pause() { playing_ = false; }
  // Play when paused, pause when playing.
  void toggle(const Timeline& tl);
  bool playing() const { return playing_; }

  // Moves the playhead to the start of frame (clamped to the range); keeps playing if it was.
  void seekFrame(int frame, const Timeline& tl);

  // Advances by dtSec of wall-clock time at tl.playbackSpeed. At the end of
  // the range it wraps (tl.loop) or stops on the last frame. Returns the frame
  // to show. Negative or non-finite dt is ignored.
  int advance(double dtSec, const Timeline& tl);

  double timeSec() const { return timeSec_; }
  // floor(time * fps), with a tolerance of 1e-6 frame so accumulated rounding
  // never shows the previous frame.
  int frame(const Timeline& tl) const;

 private:
  void wrapOrClamp(const Timeline& tl);
  double timeSec_ = 0.0;
  double compensation_ = 0.0;  // Kahan summation term: no drift over long sessions
  bool playing_ = false;
};

// First and one-past-last time of the range [frameStart, frameEnd] in seconds
// (the last frame is shown for a whole frame period).
double rangeStartSec(const Timeline& tl);
double rangeEndSec(const Timeline& tl);

}  // namespace animorph
