#include "core/poly/frame_sequence.h"

#include <chrono>
#include <string>

namespace animorph {

Result<std::optional<PolygonizeGrid>> frameSequenceGrid(int count, const std::function<FieldProgram(int)>& programOf,
                                                        const FrameSequenceSettings& settings, bool* cancelled) {
  PolygonizeSettings ps;
  ps.resolution = settings.resolution;
  SequenceGrid grid;
  for (int k = 0; k < count; ++k) {
    if (settings.cancel && settings.cancel->load(std::memory_order_relaxed)) {
      if (cancelled) *cancelled = true;
      return std::optional<PolygonizeGrid>();
    }
    if (Status s = grid.add(programOf(k), ps); !s) return Error{"frame " + std::to_string(k) + ": " + s.error()};
  }
  return grid.grid();
}

Result<FrameSequenceStats> polygonizeFrameSequence(int count, const std::function<FieldProgram(int)>& programOf,
                                                   const std::function<Status(int, PolygonizeResult&&)>& frameDone,
                                                   const FrameSequenceSettings& settings) {
  FrameSequenceStats stats;
  auto stopped = [&] { return settings.cancel && settings.cancel->load(std::memory_order_relaxed); };
  PolygonizeSettings ps;
  ps.resolution = settings.resolution;
  ps.threads = settings.threads;
  ps.cancel = settings.cancel;
  ps.colors = settings.colors;
  const auto t0 = std::chrono::steady_clock::now();
  auto grid = frameSequenceGrid(count, programOf, settings, &stats.cancelled);
  if (!grid) return Error{grid.error()};
  if (stats.cancelled) return stats;
  stats.gridMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  // No frame has an inside: each frame alone gives its (empty) mesh.
  if (*grid) {
    ps.grid = **grid;
    stats.grid = **grid;
  } else {
    stats.grid.empty = true;
  }
  PolygonizeHistory history;
  ps.history = &history;
  ps.reuseToleranceCells = settings.reuseToleranceCells;
  for (int k = 0; k < count; ++k) {
    auto r = polygonize(programOf(k), ps);
    if (!r) return Error{"frame " + std::to_string(k) + ": " + r.error()};
    if (r->cancelled || stopped()) {
      stats.cancelled = true;
      return stats;
    }
    stats.blocksEvaluated += r->stats.blocksEvaluated;
    stats.blocksReused += r->stats.blocksReused;
    if (Status s = frameDone(k, std::move(*r)); !s) return Error{s.error()};
  }
  return stats;
}

}  // namespace animorph
