#include "core/export/bake_route.h"

#include <chrono>
#include <memory>
#include <mutex>

#include "core/export/bake_continuity.h"
#include "core/export/bake_frame_loop.h"
#include "core/export/bake_sink.h"
#include "core/poly/frame_sequence.h"

namespace animorph {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Counts a baked frame into the report's stages (from any worker thread).
class StageCounter {
 public:
  void add(MorphStage stage, size_t triangles) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++frames_[size_t(stage)];
    triangles_[size_t(stage)] += triangles;
  }
  void into(BakeReport& r) const {
    r.stageFrames = frames_;
    r.stageTriangles = triangles_;
    for (size_t t : triangles_) r.triangles += t;
  }

 private:
  std::mutex mutex_;
  std::array<int, 5> frames_{};
  std::array<size_t, 5> triangles_{};
};

// The frames one at a time or in parallel, each on its own grid: a morph's frames, or an
// animorphosis' without coherence.
Status bakeFramesApart(const ProjectFrames& frames, const BakeSettings& s, BakeSink& sink, StageCounter& stages,
                       BakeContinuityMeter* meter, JobProgress& progress) {
  const int count = s.last - s.first + 1;
  FrameBakeSettings fs;
  fs.resolution = s.resolution;
  fs.threads = s.jobs > 1 ? 1 : 0;
  fs.cancel = progress.cancelFlag();
  fs.implicitStage = s.implicitStage;
  fs.keepInnerShell = s.keepInnerShell;
  fs.colors = s.colors;
  fs.measure = meter != nullptr;
  const bool meshes = sink.wantsMeshes() || meter;
  return runFrameLoop(s.first, count, s.jobs, progress, [&](int k) -> Status {
    const int f = s.first + k;
    if (meshes) {
      auto baked = frames.frame(f, fs);
      if (!baked) return Error{baked.error()};
      stages.add(baked->stage, baked->mesh.triangleCount());
      if (meter) meter->add(k, *baked);
      if (Status st = sink.addMesh(k, std::move(baked->mesh)); !st) return st;
    } else {
      stages.add(frames.stageAt(f), 0);
    }
    if (!sink.wantsVolumes()) return Status::success();
    auto band = frames.levelSet(f, s.resolution, fs.cancel, fs.threads, s.colors);
    if (!band) return Error{band.error()};
    if (progress.cancelled() || (*band && (*band)->cancelled)) return jobCancelled();
    return sink.addVolume(k, *band ? &**band : nullptr);
  }, s.frameDone);
}

// An animorphosis' frames in order on one grid with temporal coherence (poly/frame_sequence.h).
Status bakeAnimorphosisSequence(const ProjectFrames& frames, const BakeSettings& s, BakeSink& sink,
                                StageCounter& stages, BakeReport& report, JobProgress& progress) {
  const int count = s.last - s.first + 1;
  FrameSequenceSettings fs;
  fs.resolution = s.resolution;
  fs.reuseToleranceCells = s.coherence;
  fs.colors = s.colors;
  fs.cancel = progress.cancelFlag();
  auto programOf = [&](int k) { return frames.animorphosisProgram(s.first + k); };
  auto stats = polygonizeFrameSequence(
      count, programOf,
      [&](int k, PolygonizeResult&& r) -> Status {
        const int f = s.first + k;
        progress.setStage("baking frame " + std::to_string(f) + " (" + std::to_string(k + 1) + " of " +
                          std::to_string(count) + ")");
        Status st;
        if (sink.wantsVolumes()) {
          auto band = fieldLevelSet(programOf(k), s.resolution, 0, fs.cancel, s.colors);
          if (!band) st = Error{band.error()};
          else if (progress.cancelled() || (*band)->cancelled) return jobCancelled();
          else st = sink.addVolume(k, &**band);
        }
        if (st) {
          stages.add(MorphStage::Morph, r.mesh.triangleCount());
          st = sink.addMesh(k, std::move(r.mesh));
        }
        if (!st) return Error{"frame " + std::to_string(f) + ": " + st.error()};
        progress.advance();
        if (s.frameDone) s.frameDone(f);
        return Status::success();
      },
      fs);
  if (!stats) return Error{stats.error()};  // a cancel inside comes back as jobCancelled()'s error
  if (stats->cancelled || progress.cancelled()) return jobCancelled();
  BakeCoherence c;
  c.toleranceCells = s.coherence;
  c.blocksEvaluated = stats->blocksEvaluated;
  c.blocksReused = stats->blocksReused;
  c.gridCells = {stats->grid.cells[0], stats->grid.cells[1], stats->grid.cells[2]};
  report.coherence = c;
  return Status::success();
}

}  // namespace

std::string bakeSettingsProblem(const BakeSettings& s) {
  if (s.first < 0) return "frame " + std::to_string(s.first) + " is negative (frames start at 0)";
  if (s.last < s.first)
    return "the last frame " + std::to_string(s.last) + " is before the first " + std::to_string(s.first);
  if (s.resolution < 2 || s.resolution > 1024)
    return "resolution " + std::to_string(s.resolution) + " is outside 2..1024";
  if (s.jobs < 1 || s.jobs > 256) return std::to_string(s.jobs) + " parallel frames: expected 1..256";
  if (!(s.coherence >= 0.0f && s.coherence <= 0.5f))
    return "coherence " + std::to_string(s.coherence) + " cells: expected 0..0.5 (0: off)";
  if ((s.outputs.ply || s.outputs.obj) && s.outputs.dir.empty()) return "no folder chosen for the frame sequence";
  return {};
}

Result<BakeReport> bakeProject(const ProjectFrames& frames, const BakeSettings& s, JobProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::string why = bakeSettingsProblem(s); !why.empty()) return Error{why};
  const int count = s.last - s.first + 1;
  BakeSink sink(s.outputs, s.first, count, frames.timeline().fps);
  if (Status st = sink.open(); !st) return Error{st.error()};
  BakeReport report;
  report.first = s.first;
  report.last = s.last;
  report.frames = count;
  report.animorphosis = frames.animorphosis() != nullptr;
  if (report.animorphosis) report.animorphosisNodes = frames.animorphosis()->size();
  std::unique_ptr<BakeContinuityMeter> meter;
  if (frames.morph() && s.measureContinuity)
    meter = std::make_unique<BakeContinuityMeter>(*frames.morph(), s.first, count, s.resolution);
  StageCounter stages;
  Status baked = report.animorphosis && s.coherence > 0.0f
                     ? bakeAnimorphosisSequence(frames, s, sink, stages, report, progress)
                     : bakeFramesApart(frames, s, sink, stages, meter.get(), progress);
  if (!baked) return isJobCancelled(baked) ? jobCancelled() : Error{baked.error()};
  if (progress.cancelled()) return jobCancelled();
  stages.into(report);
  report.frameSeconds = secondsSince(t0);
  if (meter) report.continuity = meter->summary();  // the characters' own motion measured here
  if (Status st = sink.finish(report); !st) return Error{st.error()};
  report.seconds = secondsSince(t0);
  return report;
}

}  // namespace animorph
