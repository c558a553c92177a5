#pragma once
// File > Export... (and tests): bakes a project's morph (or, when it has only an animorphosis,
// its C(t)) frame by frame on the CPU and writes the frames as ExportSettings say, under a
// JobProgress (progress counts frames; cancel is polled between frames and inside the
// polygonisation). Meant to run as a BackgroundJob on a copy of the project.
//
// No half-written output: sequence frames are written as FINAL.part-PID and renamed when every
// frame is done; the .glb is assembled in memory and written atomically at the end. A cancelled
// or failed export removes its temporaries and leaves what was at the output before.
#include <string>
#include <vector>

#include "core/project/project.h"
#include "core/util/background_job.h"
#include "core/util/result.h"

namespace animorph {

// The frames an export covers: the settings' range, or the timeline's when useTimeline.
void exportFrameRange(const Project& p, const ExportSettings& s, int& first, int& last);

// Where the export writes: the .glb, or the sequence's folder; relative paths are taken from
// baseDir (the project's folder).
std::string exportOutputPath(const ExportSettings& s, const std::string& baseDir);

struct ExportReport {
  std::vector<std::string> files;  // what was written, in frame order (one .glb, or one per frame)
  int frames = 0;
  int framesWithoutField = 0;      // VDB: skinned-mesh frames, which have no level set (no file)
  size_t triangles = 0;            // over all frames
  double seconds = 0.0;
};

// Runs the export. Errors name the project element or the file and the reason; a cancelled
// export returns jobCancelled().
Result<ExportReport> exportProject(const Project& p, const std::string& baseDir, const ExportSettings& s,
                                   JobProgress& progress);

}  // namespace animorph
