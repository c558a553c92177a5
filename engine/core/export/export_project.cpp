#include "core/export/export_project.h"

#include <chrono>
#include <filesystem>

#include "core/export/frame_files.h"
#include "core/export/project_frames.h"
#include "core/io/gltf_sequence_export.h"
#include "core/io/vdb_export.h"
#include "core/io/mesh_io.h"

namespace animorph {
namespace fs = std::filesystem;

void exportFrameRange(const Project& p, const ExportSettings& s, int& first, int& last) {
  first = s.useTimeline ? p.timeline.frameStart : s.first;
  last = s.useTimeline ? p.timeline.frameEnd : s.last;
}

std::string exportOutputPath(const ExportSettings& s, const std::string& baseDir) {
  return resolveOutputPath(s.output, baseDir);
}

Result<ExportReport> exportProject(const Project& p, const std::string& baseDir, const ExportSettings& s,
                                   JobProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  int first = 0, last = 0;
  exportFrameRange(p, s, first, last);
  if (last < first) return Error{"export: the last frame " + std::to_string(last) + " is before the first " +
                                 std::to_string(first)};
  if (first < 0) return Error{"export: frame " + std::to_string(first) + " is negative (frames start at 0)"};
  if (s.resolution < 2 || s.resolution > 1024)
    return Error{"export: resolution " + std::to_string(s.resolution) + " is outside 2..1024"};
  const std::string out = exportOutputPath(s, baseDir);
  if (out.empty()) return Error{"export: no output path chosen"};
  const int count = last - first + 1;
  progress.setTotal(count);
  progress.setStage("preparing");

  auto frames = ProjectFrames::prepare(p, baseDir);
  if (!frames) return Error{"export: " + frames.error()};

  std::error_code ec;
  const bool gltf = s.format == ExportFormat::GltfAnimated;
  const fs::path dir = gltf ? fs::path(out).parent_path() : fs::path(out);
  if (!dir.empty()) fs::create_directories(dir, ec);
  if (ec) return Error{dir.string() + ": cannot create the folder: " + ec.message()};
  const std::string prefix = framePrefix(p.name);
  std::unique_ptr<GltfSequenceWriter> sequence;
  if (gltf) {
    GltfSequenceOptions so;
    so.name = prefix;
    so.fps = p.timeline.fps;
    so.firstFrame = first;
    sequence = std::make_unique<GltfSequenceWriter>(so);
  }
  StagedFiles staged;
  ExportReport report;
  for (int k = 0; k < count; ++k) {
    if (progress.cancelled()) return jobCancelled();
    const int f = first + k;
    progress.setStage("frame " + std::to_string(f) + " (" + std::to_string(k + 1) + " of " + std::to_string(count) +
                      ")");
    if (s.format == ExportFormat::VdbSequence) {
      // The frame's field as a level set (no mesh); a skinned-mesh frame has none.
      auto band = frames->levelSet(f, s.resolution, progress.cancelFlag());
      if (!band) return Error{"export: frame " + std::to_string(f) + ": " + band.error()};
      if (progress.cancelled() || (*band && (*band)->cancelled)) return jobCancelled();
      if (*band) {
        const std::string final = frameFileName(dir.string(), prefix, f, "vdb");
        if (Status st = writeVdbLevelSet(**band, staged.stage(final)); !st)
          return Error{"export: frame " + std::to_string(f) + ": " + st.error()};
        report.files.push_back(final);
      } else {
        ++report.framesWithoutField;
      }
      progress.setDone(k + 1);
      continue;
    }
    auto baked = frames->mesh(f, s.resolution, progress.cancelFlag());
    if (!baked)
      return progress.cancelled() ? jobCancelled() : Error{"export: frame " + std::to_string(f) + ": " + baked.error()};
    TriangleMesh mesh = std::move(*baked);
    report.triangles += mesh.triangleCount();
    Status st;
    if (sequence) {
      st = sequence->addFrame(mesh);
    } else {
      const char* ext = s.format == ExportFormat::ObjSequence ? "obj" : "ply";
      const std::string final = frameFileName(dir.string(), prefix, f, ext);
      const std::string tmp = staged.stage(final);
      st = s.format == ExportFormat::ObjSequence ? writeObj(mesh, tmp) : writePly(mesh, tmp);
      if (st) report.files.push_back(final);
    }
    if (!st) return Error{"export: frame " + std::to_string(f) + ": " + st.error()};
    progress.setDone(k + 1);
  }
  if (progress.cancelled()) return jobCancelled();
  if (s.format == ExportFormat::VdbSequence && report.files.empty())
    return Error{"export: frames " + std::to_string(first) + ".." + std::to_string(last) +
                 " are all skinned meshes (before B or after C): none has an implicit field to write as a VDB level set"};
  if (sequence) {
    progress.setStage("writing " + fs::path(out).filename().string());
    if (Status st = writeGltfSequence(*sequence, out); !st) return Error{"export: " + st.error()};
    report.files.push_back(out);
  } else if (Status st = staged.commit(); !st) {
    return Error{"export: " + st.error()};
  }
  report.frames = count;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace animorph
