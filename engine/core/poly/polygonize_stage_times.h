#pragma once
// Measuring only (animorph-cli bench bake-scaling): the wall time of each stage of polygonize()
// (poly/polygonizer.cpp, one PolygonizeRun member per stage), so that a stage whose cost grows
// with the grid's volume instead of its surface shows. Kept apart from polygonizer.h so that the
// many files including that one do not depend on it.
#include <cstddef>

namespace animorph {

struct PolygonizeStageTimes {
  size_t calls = 0;          // polygonize() calls added
  double setupMs = 0.0;      // grid, run state, history taken, every primitive specialised
  double superblocksMs = 0.0;  // superblock culling (coarse level)
  double pairsMs = 0.0;      // pair candidate lists and pair culling (middle level)
  double blocksMs = 0.0;     // every block: culled, reused or evaluated and triangulated (parallel)
  double stitchMs = 0.0;     // global numbering and triangle corners resolved (parallel)
  double orphansMs = 0.0;    // edges no owner block made
  double historyMs = 0.0;    // the next frame's history saved
  double colorsMs = 0.0;     // vertex colours made after the mesh (settings.colors with a colorProgram)
  double totalMs = 0.0;      // the whole call (PolygonizeStats::milliseconds)
  size_t blocksTotal = 0;    // 8^3-cell blocks of the grids, summed
  // Blocks the fine level tested one by one (not culled or reused with their superblock or pair).
  size_t blocksVisited = 0;
  size_t blocksEvaluated = 0;    // blocks evaluated (not culled, not reused)
  size_t blocksWithSurface = 0;  // evaluated blocks that made triangles
};

// While sink is set, every polygonize() call made on this thread adds its stage times to *sink
// (null: none, the default). The sink must outlive the calls; one thread's setting only.
void setPolygonizeStageTimes(PolygonizeStageTimes* sink);

// Measuring and testing only: while false, polygonize() calls on this thread skip the pair level's
// culling (every block of a superblock that is not culled is tested one by one, as before it
// existed; the same mesh, more blocks tested). On by default; one thread's setting only.
void setPolygonizePairCulling(bool on);

}  // namespace animorph
