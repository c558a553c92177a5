#include "gpu/frame/playblast.h"

#include <chrono>
#include <filesystem>

#include "core/export/frame_files.h"
#include "core/export/frame_stage.h"
#include "core/export/bake_route.h"
#include "core/export/project_frames.h"
#include "gpu/frame/mesh_sequence_renderer.h"

namespace animorph::gpu {
namespace fs = std::filesystem;

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

Result<PlayblastReport> playblastMeshes(const std::vector<TriangleMesh>& meshes, const ViewOptions& view,
                                        const Mp4Options& o, const std::optional<OrbitCamera>& camera,
                                        JobProgress* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (meshes.empty()) return Error{o.path + ": no frames to draw"};
  auto renderer = MeshSequenceRenderer::create(o.width, o.height, view);
  if (!renderer) return Error{"playblast: " + renderer.error()};
  if (camera) {
    (*renderer)->setCamera(*camera);
  } else {  // one camera for the whole sequence, framing every frame
    Bounds all;
    for (const auto& m : meshes)
      for (const auto& p : m.positions) all.add(p);
    (*renderer)->frameBounds(all);
  }
  auto writer = Mp4Writer::start(o);
  if (!writer) return Error{writer.error()};
  const double before = progress ? progress->done() : 0.0;
  for (size_t k = 0; k < meshes.size(); ++k) {
    if (progress && progress->cancelled()) return jobCancelled();  // the writer removes its temporary
    if (progress)
      progress->setStage("drawing frame " + std::to_string(o.firstFrame + int(k)) + " (" + std::to_string(k + 1) +
                         " of " + std::to_string(meshes.size()) + ")");
    auto image = (*renderer)->render(meshes[k]);
    if (!image) return Error{"playblast: frame " + std::to_string(o.firstFrame + int(k)) + ": " + image.error()};
    if (Status st = (*writer)->addFrame((*image)->pixels); !st) return Error{st.error()};
    if (progress) {  // in seconds: the rate so far times the frames left
      const double spent = secondsSince(t0);
      progress->setTotal(before + spent / double(k + 1) * double(meshes.size()));
      progress->setDone(before + spent);
    }
  }
  if (Status st = (*writer)->finish(); !st) return Error{st.error()};
  if (uint32_t n = (*renderer)->validationErrors(); n > 0)
    return Error{"playblast: " + std::to_string(n) + " Vulkan validation error(s) while drawing (" + o.path +
                 " was written)"};
  PlayblastReport r;
  r.file = o.path;
  r.frames = int(meshes.size());
  r.width = int(o.width);
  r.height = int(o.height);
  r.pictureSeconds = secondsSince(t0);
  r.seconds = r.pictureSeconds;
  r.device = (*renderer)->deviceName();
  return r;
}

Result<PlayblastReport> playblastProject(const Project& project, const std::string& baseDir,
                                         const PlayblastSettings& s, const std::optional<OrbitCamera>& camera,
                                         JobProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  int first = 0, last = 0;
  playblastFrameRange(project, s, first, last);
  if (first < 0) return Error{"playblast: frame " + std::to_string(first) + " is negative (frames start at 0)"};
  if (last < first)
    return Error{"playblast: the last frame " + std::to_string(last) + " is before the first " + std::to_string(first)};
  if (std::string why = playblastSizeProblem(s); !why.empty()) return Error{"playblast: " + why};
  const std::string out = resolveOutputPath(s.output, baseDir);
  if (out.empty()) return Error{"playblast: no output file chosen"};
  const int count = last - first + 1;
  progress.setTotal(2.0 * count);  // baked, then drawn and encoded
  progress.setStage("preparing");
  auto frames = ProjectFrames::prepare(project, baseDir);
  if (!frames) return Error{"playblast: " + frames.error()};
  BakeSettings bake;  // the frames kept in memory, no file (export/bake_route.h)
  bake.first = first;
  bake.last = last;
  bake.resolution = s.resolution;
  bake.outputs.keepMeshes = true;
  auto baked = bakeProject(*frames, bake, progress);
  if (!baked) return isJobCancelled(Status(Error{baked.error()})) ? jobCancelled() : Error{"playblast: " + baked.error()};
  std::vector<TriangleMesh> meshes = std::move(baked->meshes);
  // From here on progress counts seconds of work: the baking took bakeSec; drawing a frame is
  // guessed to cost as much as baking one until the first is drawn (playblastMeshes).
  const double bakeSec = secondsSince(t0);
  progress.setDone(bakeSec);
  progress.setTotal(2.0 * bakeSec);
  std::error_code ec;
  if (fs::path(out).has_parent_path()) fs::create_directories(fs::path(out).parent_path(), ec);
  if (ec) return Error{out + ": cannot create its folder: " + ec.message()};
  Mp4Options o;
  o.path = out;
  o.width = uint32_t(s.width);
  o.height = uint32_t(s.height);
  o.fps = project.timeline.fps;
  o.burnIn = s.burnIn;
  o.firstFrame = first;
  o.stages = frameStageSpans(project, first, last);
  auto r = playblastMeshes(meshes, project.view, o, s.viewportCamera ? camera : std::nullopt, &progress);
  if (!r) return r;
  r->seconds = secondsSince(t0);
  return r;
}

}  // namespace animorph::gpu
