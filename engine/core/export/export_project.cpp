#include "core/export/export_project.h"

#include <filesystem>

#include "core/export/bake_route.h"
#include "core/export/frame_files.h"
#include "core/export/project_frames.h"

namespace animorph {
namespace fs = std::filesystem;

void exportFrameRange(const Project& p, const ExportSettings& s, int& first, int& last) {
  first = s.useTimeline ? p.timeline.frameStart : s.first;
  last = s.useTimeline ? p.timeline.frameEnd : s.last;
}

std::string exportOutputPath(const ExportSettings& s, const std::string& baseDir) {
  return resolveOutputPath(s.output, baseDir);
}

namespace {

// The bake an export runs: its frames, one at a time (the polygoniser uses every thread), each on
// its own grid, into the one output its format names.
BakeSettings exportBakeSettings(const Project& p, const ExportSettings& s, const std::string& out) {
  BakeSettings b;
  exportFrameRange(p, s, b.first, b.last);
  b.resolution = s.resolution;
  b.outputs.prefix = framePrefix(p.name);
  switch (s.format) {
    case ExportFormat::GltfAnimated: b.outputs.gltf = out; break;
    case ExportFormat::PlySequence: b.outputs.dir = out, b.outputs.ply = true; break;
    case ExportFormat::ObjSequence: b.outputs.dir = out, b.outputs.obj = true; break;
    case ExportFormat::VdbSequence: b.outputs.vdbDir = out; break;
  }
  return b;
}

}  // namespace

Result<ExportReport> exportProject(const Project& p, const std::string& baseDir, const ExportSettings& s,
                                   JobProgress& progress) {
  const std::string out = exportOutputPath(s, baseDir);
  const BakeSettings bake = exportBakeSettings(p, s, out);
  std::string why = bakeSettingsProblem(bake);
  if (out.empty()) {  // the frames and resolution first, then the missing path (not the folder it lacks)
    BakeSettings frames = bake;
    frames.outputs = BakeOutputs{};
    why = bakeSettingsProblem(frames);
    if (why.empty()) why = "no output path chosen";
  }
  if (!why.empty()) return Error{"export: " + why};
  progress.setTotal(bake.last - bake.first + 1);
  progress.setDone(0);
  progress.setStage("preparing");
  auto frames = ProjectFrames::prepare(p, baseDir);
  if (!frames) return Error{"export: " + frames.error()};
  auto baked = bakeProject(*frames, bake, progress);
  if (!baked) return isJobCancelled(Status(Error{baked.error()})) ? jobCancelled() : Error{"export: " + baked.error()};
  ExportReport report;
  report.files = std::move(baked->files);
  report.frames = baked->frames;
  report.framesWithoutField = baked->framesWithoutField;
  report.triangles = baked->triangles;
  report.seconds = baked->seconds;
  return report;
}

}  // namespace animorph
