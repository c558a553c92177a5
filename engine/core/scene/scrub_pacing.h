#pragma once
// Frame pacing while the timeline is scrubbed and a CPU preview is computing. Between two preview
// meshes nothing on screen changes but the playhead and the actors that are not implicit, so the
// frame loop need not redraw on every mouse motion (on a CPU Vulkan device a frame is ~16-20 ms of
// a core the preview worker needs). The paced loop draws at once when a preview mesh is published,
// draws input (the cursor moved the playhead) no more often than once an interval -- one frame of
// the project, between 1/60 and 1/24 s, so input waits at most one paced frame -- and otherwise
// waits (a frame all the same after kMaxWaitSec: the status bar). The worker then gets every
// hardware thread (pacedPreviewThreads). The editor's frame loop and `animorph-cli bench
// animorph-scrub` both follow it.
#include <cstdint>

namespace animorph {

class ScrubPacer {
 public:
  static constexpr double kMaxWaitSec = 0.25;

  // Whether the loop is paced: the playhead is being scrubbed and a CPU preview computes, and
  // nothing else moves on its own (playback, the GPU polygoniser, particles, screenshots).
  static bool applies(bool scrubbing, bool cpuPreviewBusy, bool otherwiseAnimating) {
    return scrubbing && cpuPreviewBusy && !otherwiseAnimating;
  }
  // The paced interval for a project at fps frames per second.
  static double intervalFor(double fps);

  explicit ScrubPacer(double intervalSec = 1.0 / 24.0) : intervalSec_(intervalSec) {}
  double intervalSec() const { return intervalSec_; }
  void setIntervalSec(double s) { intervalSec_ = s; }

  // A frame began at nowSec having taken in events window events and meshes published preview meshes
  // (PreviewPolygonizer::publishedTotal).
  void frameStarted(double nowSec, uint64_t events, uint64_t meshes) {
    frameSec_ = nowSec;
    events_ = events;
    meshes_ = meshes;
  }
  // With the counters now: 0 draws the next frame at once; else wait up to that long for events
  // (a published mesh wakes the wait) and ask again.
  double waitSec(double nowSec, uint64_t events, uint64_t meshes) const;

 private:
  double intervalSec_;
  double frameSec_ = 0.0;
  uint64_t events_ = 0, meshes_ = 0;
};

}  // namespace animorph
