#pragma once
// Frames of an animation polygonised in order with temporal coherence (a bake): every frame on one
// grid (SequenceGrid: the union of the frames' own grids at the finest of their cells), one
// PolygonizeHistory carried from frame to frame, so blocks whose field provably moved less than
// reuseToleranceCells allow are reused (polygonizer.h). Each frame's mesh has the triangles a full
// polygonisation on that grid makes, its vertices within the tolerance of that one's.
#include <atomic>
#include <functional>

#include "core/poly/polygonizer.h"

namespace animorph {

struct FrameSequenceSettings {
  int resolution = 128;              // cells along the longest side of the largest frame's own grid
  float reuseToleranceCells = 0.1f;  // PolygonizeSettings::reuseToleranceCells (0: exact reuse only)
  int threads = 0;                   // polygoniser threads; 0 = all
  const std::atomic<bool>* cancel = nullptr;  // stops between and inside frames (result: cancelled)
  bool colors = false;               // vertex colours (PolygonizeSettings::colors)
};

struct FrameSequenceStats {
  PolygonizeGrid grid;          // the grid every frame was polygonised on
  size_t blocksEvaluated = 0;   // over all frames (reused blocks count here too)
  size_t blocksReused = 0;     // taken from the frame before (blocks culled there included)
  double gridMilliseconds = 0.0;  // the first pass (each frame's program and grid)
  bool cancelled = false;
};

// The first pass alone: one grid for frames 0..count-1 (SequenceGrid over programOf(k) with
// settings' resolution). nullopt when no frame has an inside, or when settings.cancel turned true
// (then *cancelled is set). Errors: polygonizeGrid's, naming the frame.
Result<std::optional<PolygonizeGrid>> frameSequenceGrid(int count, const std::function<FieldProgram(int)>& programOf,
                                                        const FrameSequenceSettings& settings, bool* cancelled);

// programOf(k), k = 0..count-1, makes frame k's program; it is called twice per frame (the grid
// pass, then the polygonisation). frameDone(k, result) takes each frame's result in order; an
// error from it stops the run and is returned. Errors: a frame's polygoniser error, naming the frame.
Result<FrameSequenceStats> polygonizeFrameSequence(int count, const std::function<FieldProgram(int)>& programOf,
                                                   const std::function<Status(int, PolygonizeResult&&)>& frameDone,
                                                   const FrameSequenceSettings& settings);

}  // namespace animorph
