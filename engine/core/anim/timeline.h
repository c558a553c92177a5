#pragma once
// The scene's timeline: frame rate, the playback range, the current frame
// and how playback runs. Times in seconds are frame / fps (frame 0 at 0 s);
// fps is validated > 0 wherever a timeline is read (project_io.h).

namespace animorph {

struct Timeline {
  double fps = 24.0;
  int frameStart = 0;
  int frameEnd = 96;
  int currentFrame = 0;
  double playbackSpeed = 1.0;
  bool loop = true;
  bool operator==(const Timeline&) const = default;

  double frameToSec(double frame) const { return frame / fps; }
  double secToFrame(double sec) const { return sec * fps; }
  // The time shown: the start of the current frame, in seconds (0 when fps is not positive).
  double currentTimeSec() const { return fps > 0.0 ? currentFrame / fps : 0.0; }
};

}  // namespace animorph
