#pragma once
// The editor's switches for tests and benchmarks, as the frame loop applies them: --frame (once the
// project is open), --scrub/--scrub-hz (a hand dragging the timeline), --bench (frame times while
// playing or scrubbing), --screenshot/--quit, --idle-bench (frames and CPU while idle). Nothing here
// runs without its switch; the results are printed on stdout.
#include <optional>
#include <string>
#include <vector>

#include "core/anim/playback.h"
#include "core/doc/document.h"
#include "app/editor/editor_args.h"

namespace animorph {

class EditorAutomation {
 public:
  explicit EditorAutomation(const EditorArgs& args) : args_(args) {}

  // Before the UI draws frame frameCount: applies --frame once the project is open, steps --scrub,
  // or starts --bench's playback. Nothing while jobRunning (the project given on the command line
  // opens as a background job: --frame, --bench and --screenshot wait for it).
  void beforeUi(Document& doc, Playback& playback, double nowSec, int frameCount, bool jobRunning);
  // The --screenshot path on the frame it is due (once, after the first frames and --frame, with no
  // job running).
  std::optional<std::string> screenshotDue(int frameCount, bool jobRunning);
  // True when --quit ends the editor once the --screenshot is written.
  bool quitAfterScreenshot() const { return args_.quit && screenshotAt_ >= 0; }
  // True while a switch needs frames drawn one after another rather than on demand.
  bool needsFrames() const;
  // The first frame reached the window, sinceStartMs after start-up.
  void firstFrameShown(double sinceStartMs);
  // After frame frameCount: records --bench's frame time and --idle-bench's figures. True when the
  // run is over (the bench's frames measured, --quit without a screenshot, the idle time elapsed).
  bool frameDone(int frameCount, double dtSec, double nowSec, bool previewsSettled, bool continuousRedraw);
  // Before frameDone: what the frame showed (the 3D scene rendered or the kept image, the
  // project frame), listed by printBench next to each measured frame's time.
  void noteFrame(bool scenePass, int projectFrame);
  // --bench was given.
  bool benchRan() const { return args_.benchFrames > 0; }
  // --bench's figures, on exit.
  void printBench(const std::string& deviceName, const std::string& presentPath) const;

 private:
  EditorArgs args_;
  bool frameApplied_ = false;
  bool benchPlayStarted_ = false;
  int screenshotAt_ = -1;
  double scrubStartSec_ = -1.0;
  double firstFrameMs_ = -1.0;
  std::vector<double> frameMs_;
  struct FrameNote {
    bool scenePass = false;
    int projectFrame = 0;
  };
  std::vector<FrameNote> frameNotes_;  // one per measured frame, as frameMs_
  FrameNote lastNote_;
  // --bench: the editor process's processor time (all its threads) when the first measured frame
  // started, and when the last ended: frames shown per second and processor time per frame.
  double benchCpuStartSec_ = -1.0, benchCpuEndSec_ = -1.0;
  // --idle-bench: from 2 s after start-up (the project open, the previews refined), S seconds without input.
  double idleStartSec_ = -1.0, idleStartCpu_ = 0.0;
  int idleStartFrames_ = 0;
};

}  // namespace animorph
