#pragma once
// File > Export > Playblast... as the editor runs it: the settings' frames baked on the CPU
// (export/project_frames.h) and drawn offscreen into an .mp4 (export/mp4_writer.h), on a background
// job. The drawing needs a GPU device, which the core does not have: the app hands the editor a
// PlayblastRunner (frame/playblast.h, gpu::playblastProject) that does the whole job.
#include <functional>
#include <optional>
#include <string>

#include "core/project/project.h"
#include "core/util/job_progress.h"
#include "core/util/result.h"
#include "core/camera/camera.h"

namespace animorph {

struct PlayblastReport {
  std::string file;  // the .mp4 written
  int frames = 0;
  int width = 0, height = 0;
  double seconds = 0.0;          // the whole job
  double pictureSeconds = 0.0;   // rendering and encoding alone
  std::string device;            // the Vulkan device that drew the frames
};

// Runs a playblast of project (a copy; relative paths taken from baseDir) as the settings say,
// under progress (frames baked, then frames drawn; cancel polled between frames). camera: the
// viewport's camera when s.viewportCamera (the editor passes it as it was when the job started);
// none: one camera framing every frame. A cancelled job returns jobCancelled() and leaves no file.
using PlayblastRunner = std::function<Result<PlayblastReport>(const Project& project, const std::string& baseDir,
                                                              const PlayblastSettings& s,
                                                              const std::optional<OrbitCamera>& camera,
                                                              JobProgress& progress)>;

// The frames a playblast covers: the settings' range, or the timeline's when useTimeline.
void playblastFrameRange(const Project& p, const PlayblastSettings& s, int& first, int& last);

}  // namespace animorph
