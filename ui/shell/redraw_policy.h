#pragma once
// When the editor draws a frame: on demand, as Blender and Maya do. An idle
// editor waits for input instead of redrawing its whole window forty times a
// second (on a CPU Vulkan device that was both cores, all the time).
//
// The frame loop draws at once while anything moves on its own (playback,
// previews still computing, a mouse button held, start-up, benches and
// screenshots), and for a few frames after every window or input event (ImGui
// opens popups, settles hover states and replays deferred key releases on the
// frames after the event). A preview computed by the CPU worker wakes the loop
// when it publishes a mesh (the editor does not redraw while it waits, which on
// two cores leaves the worker a core). Otherwise it waits for the next event, but draws a
// frame a second all the same: autosave, the check for assets changed on
// disk and the status bar's timings run in frames, and a text field's caret
// blinks at twice that rate.
namespace animorph {

struct RedrawState {
  bool input = false;      // window or input events since the previous frame
  bool animating = false;  // something changes without input: draw the next frame at once
  bool textInput = false;  // a text field has the keyboard
  bool awaitingWork = false;  // a background job will wake the loop when it has something to show
  bool jobRunning = false;    // an editor job (open, import, export) runs: its progress panel moves
};

class RedrawPolicy {
 public:
  static constexpr int kSettleFrames = 3;
  static constexpr double kIdleTickSec = 1.0;
  static constexpr double kCaretTickSec = 0.5;
  static constexpr double kWorkPollSec = 0.25;  // awaiting work: a poll all the same, should a wake be missed
  static constexpr double kJobFrameSec = 0.1;   // a job's progress panel redrawn ten times a second

  // After a frame: how long the loop may wait for events before drawing the
  // next one; 0 draws it at once.
  double waitAfterFrame(const RedrawState& s);

 private:
  int settle_ = kSettleFrames;  // frames still to draw after the last event
};

}  // namespace animorph
