#include "app/editor/editor_automation.h"

#include <algorithm>
#include <cstdio>
#include <ctime>

namespace animorph {
namespace {

double processCpuSec() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

}  // namespace

void EditorAutomation::beforeUi(Document& doc, Playback& playback, double nowSec, int frameCount, bool jobRunning) {
  if (jobRunning) return;
  if (args_.frame >= 0 && !frameApplied_ && frameCount >= 2) {
    doc.setCurrentFrame(args_.frame);
    frameApplied_ = true;
  }
  if (args_.benchFrames > 0 && args_.scrubFrom >= 0 && frameCount >= 2) {
    // A..B..A, one step per redraw: the preview sees a new time every frame, as when dragging.
    if (scrubStartSec_ < 0.0) scrubStartSec_ = nowSec;
    const long step = args_.scrubHz > 0.0 ? long((nowSec - scrubStartSec_) * args_.scrubHz) : long(frameCount - 2);
    const int span = args_.scrubTo - args_.scrubFrom, k = int(step % (2 * span));
    doc.setCurrentFrame(args_.scrubFrom + (k <= span ? k : 2 * span - k));
  } else if (args_.benchFrames > 0 && frameCount >= 2 && !benchPlayStarted_) {
    // Once the project is open (until 2026-11-29 only on frame 2, while the open job still ran: the
    // demo never played and the bench timed a still scene).
    if (!playback.playing()) playback.toggle(doc.project().timeline);
    benchPlayStarted_ = true;
  }
}

std::optional<std::string> EditorAutomation::screenshotDue(int frameCount, bool jobRunning) {
  if (args_.screenshot.empty() || screenshotAt_ >= 0 || frameApplied_ != (args_.frame >= 0) || frameCount < 6 ||
      jobRunning)
    return std::nullopt;
  screenshotAt_ = frameCount;
  return args_.screenshot;
}

bool EditorAutomation::needsFrames() const {
  return args_.benchFrames > 0 || args_.quit || !args_.screenshot.empty() || (args_.frame >= 0 && !frameApplied_);
}

void EditorAutomation::firstFrameShown(double sinceStartMs) {
  if (firstFrameMs_ < 0.0) firstFrameMs_ = sinceStartMs;
}

bool EditorAutomation::frameDone(int frameCount, double dtSec, double nowSec, bool previewsSettled,
                                 bool continuousRedraw) {
  if (args_.benchFrames > 0 && frameCount >= 10 && benchCpuStartSec_ < 0.0) benchCpuStartSec_ = processCpuSec();
  if (args_.benchFrames > 0 && frameCount > 10) {
    frameMs_.push_back(dtSec * 1000.0);
    frameNotes_.push_back(lastNote_);
    if (static_cast<int>(frameMs_.size()) >= args_.benchFrames) {
      benchCpuEndSec_ = processCpuSec();
      return true;
    }
  }
  if (args_.screenshot.empty() && args_.quit && frameCount > 3) return true;
  if (args_.idleBenchSec > 0.0) {
    if (idleStartSec_ < 0.0 && ((nowSec >= 2.0 && previewsSettled) || nowSec >= 30.0)) {  // (a preview that never settles)
      idleStartSec_ = nowSec;
      idleStartCpu_ = processCpuSec();
      idleStartFrames_ = frameCount;
    } else if (idleStartSec_ >= 0.0 && nowSec - idleStartSec_ >= args_.idleBenchSec) {
      const double sec = nowSec - idleStartSec_;
      std::printf("idle over %.1f s: %d frames, CPU %.1f ms per second (%s redraw)\n", sec, frameCount - idleStartFrames_,
                  1e3 * (processCpuSec() - idleStartCpu_) / sec, continuousRedraw ? "continuous" : "on-demand");
      return true;
    }
  }
  return false;
}

void EditorAutomation::noteFrame(bool scenePass, int projectFrame) {
  lastNote_ = FrameNote{scenePass, projectFrame};
}

void EditorAutomation::printBench(const std::string& deviceName, const std::string& presentPath) const {
  if (args_.benchFrames <= 0) return;
  std::printf("start to first frame: %.1f ms\n", firstFrameMs_);
  std::printf("present: %s\n", presentPath.c_str());
  std::printf("frame time over %zu frames: p50 %.2f ms, p95 %.2f ms, max %.2f ms (device: %s)\n", frameMs_.size(),
              percentile(frameMs_, 0.5), percentile(frameMs_, 0.95), percentile(frameMs_, 1.0), deviceName.c_str());
  // Which frames make the p95: each measured frame's wall time, its project frame, S where it
  // rendered the 3D scene (else it showed the kept image).
  std::printf("frame times (ms@project frame, S: scene rendered):");
  for (size_t i = 0; i < frameMs_.size(); ++i)
    std::printf(" %.1f@%d%s", frameMs_[i], frameNotes_[i].projectFrame, frameNotes_[i].scenePass ? "S" : "");
  std::printf("\n");
  // Throughput: the frames the window showed over the wall time they took (not 1000 / a median).
  double wallMs = 0.0;
  for (double ms : frameMs_) wallMs += ms;
  const double cpuMs = benchCpuEndSec_ >= 0.0 ? 1e3 * (benchCpuEndSec_ - benchCpuStartSec_) : -1.0;
  std::printf("frames shown: %zu in %.1f ms wall, %.1f ms processor (editor process, all threads)\n", frameMs_.size(),
              wallMs, cpuMs);
}

}  // namespace animorph
