#pragma once
// CPU polygoniser (docs/design.md §6): marching cubes over a FieldProgram on a
// regular grid, vertices shared by edge id (watertight, consistently oriented,
// manifold), normals from the field gradient, coarse-to-fine block culling
// (per-block primitive lists and interval bounds), parallel with TBB.
#include <atomic>
#include <functional>
#include <memory>
#include <optional>

#include "core/field/field_program.h"
#include "core/math/bounds.h"
#include "core/poly/mesh.h"
#include "core/util/result.h"

namespace animorph {

// The grid polygonize() samples the program on (the same settings give the same grid): corner
// (i, j, k), 0 <= i <= cells[0] ..., at origin + cellSize * (i, j, k). empty: the field is inside
// nowhere (polygonize returns an empty mesh). Errors as polygonize's.
struct PolygonizeGrid {
  glm::vec3 origin{0.0f};
  float cellSize = 0.0f;
  int cells[3] = {0, 0, 0};
  bool empty = false;
};
// Temporal coherence between successive polygonisations (a bake, the editor scrubbing): with the
// same grid, culling on and a program of the same structure (same operators, primitive counts and
// operator parameters), a block whose primitives did not change since the previous call (same
// data, same bounds, same maps above them; compared value by value, no tolerance) has the same
// output, which is reused instead of being culled and evaluated again. The mesh is exactly the one
// a full sweep makes; anything else (another grid, structure or threshold) is a full sweep, except
// a grid on the same lattice moved by whole superblocks (scrubbingGrid), whose shared blocks off
// the grids' boundaries are kept. With
// PolygonizeSettings::reuseToleranceCells, blocks whose primitives moved by a provably small amount
// are reused too (the grid must still be the same: give the frames one bounds override). One
// history per sequence of frames, used by one polygonisation at a time.
class PolygonizeHistory {
 public:
  PolygonizeHistory();
  ~PolygonizeHistory();
  PolygonizeHistory(const PolygonizeHistory&) = delete;
  PolygonizeHistory& operator=(const PolygonizeHistory&) = delete;
  void clear();  // the next call is a full sweep
  // The grid of the frame it holds (nullopt: none, or a frame without a culled sweep).
  std::optional<PolygonizeGrid> grid() const;
  struct State;  // the previous frame: grid, program, superblock primitive lists, block outputs

 private:
  friend struct PolygonizeHistoryAccess;
  std::unique_ptr<State> state_;
};

struct PolygonizeSettings {
  // Cells along the longest side of the grid bounds (cells are cubes). Larger:
  // finer mesh; cost grows with the surface (culling on) or the volume (off). 2..2048.
  int resolution = 128;
  // Grid bounds; default: the program's bounds, tightened by interval
  // subdivision, grown by marginCells on every side.
  // A surface cut by these bounds is closed by the grid boundary (treated as outside).
  std::optional<Bounds> bounds;
  float marginCells = 2.0f;
  // This exact grid instead of the one resolution, bounds and marginCells make (a sequence of frames
  // on one grid, for a PolygonizeHistory: sequenceGrid, scrubbingGrid). Needs cellSize > 0 and
  // 1..2048 cells per axis.
  std::optional<PolygonizeGrid> grid;
  // Skip blocks no primitive reaches or whose field interval has one sign. Off:
  // every grid corner is evaluated with every primitive (same mesh, slower).
  bool culling = true;
  // With culling: a block reached by many primitives that the evaluator cannot skip against a
  // run of points (convolution segments, capsules) evaluates each 4^3-cell sub-block with only
  // the primitives reaching it. Skeletal primitives (points: particles) need no lists: the block's
  // corners and vertices are evaluated one sub-block at a time, and the evaluator skips those
  // whose reach misses the run (docs/particles.md, "Speed"). Same mesh; off only to measure.
  bool subBlockLists = true;
  // Measuring only: the lists also for skeletal primitives (as before: slower, same mesh).
  bool subBlockListsForSkeletal = false;
  // Worker threads; 0 = all hardware threads.
  int threads = 0;
  // Called with the fraction done (0..1), from worker threads, one call at a time.
  std::function<void(float)> progress;
  // When set to true the run stops early and returns cancelled = true, empty mesh.
  const std::atomic<bool>* cancel = nullptr;
  // Temporal coherence (see PolygonizeHistory): read, then replaced by this call's frame.
  PolygonizeHistory* history = nullptr;
  // With a history: 0 reuses a block only when nothing reaching it changed (the mesh is exactly a
  // full sweep's). Above 0, a block is also reused when the field provably moved there so little
  // (program_change.h: per-primitive change bounds, summed since the block was made) that no corner
  // of its cells changes sign and none of its vertices moves by more than this many cells along its
  // edge: the mesh then has a full sweep's triangles and vertex count, its vertices within this
  // many cells of a full sweep's; the reused normals are the older frame's. 0.1 is a good value.
  float reuseToleranceCells = 0.0f;
  // Vertex colours (TriangleMesh::colors, linear): the surface colour of the program's primitives
  // at each vertex (field/surface_color.h), equal to the whole program's colour walk. Made by each
  // block in its own thread with the block's specialised programs (only what reaches the vertex);
  // a history keeps them with a kept block (coloured again when a colour reaching it changed; a
  // block kept within reuseToleranceCells keeps its older vertices and their colours, as its
  // normals). With colorProgram, after the mesh instead, in runs of vertices between which
  // cancel is polled (a cancel there gives the cancelled, empty result). Off: none.
  bool colors = false;
  // With colors: the program the colours are evaluated on instead of the polygonised one (a
  // finished program with the same surface whose primitives carry finer colours: a morph's
  // stand-ins split into their colour samples, standin/standin_colors.h). Null: the program itself.
  const FieldProgram* colorProgram = nullptr;
};

struct PolygonizeStats {
  int gridX = 0, gridY = 0, gridZ = 0;  // cells per axis
  float cellSize = 0.0f;
  size_t blocksTotal = 0;               // 8^3-cell blocks in the grid
  size_t blocksCulled = 0;              // skipped: no primitive, or one-signed interval
  size_t blocksEvaluated = 0;
  size_t blocksWithSurface = 0;         // evaluated blocks that produced triangles
  size_t cellsVisited = 0;              // cells of evaluated blocks
  size_t pointsEvaluated = 0;           // field evaluations (grid corners + normals)
  // (point, primitive) pairs given to the evaluator (it skips skeletal ones missing a run of points)
  size_t primitiveEvaluations = 0;
  size_t orphanVertices = 0;            // edge vertices their owner block did not make (should be 0)
  size_t blocksReused = 0;              // with a history: blocks taken from the previous frame
                                        // (counted in blocksCulled / blocksEvaluated as before)
  double milliseconds = 0.0;
  // The vertex colours (settings.colors): made per block, the blocks' colour work summed over their
  // threads (processor time, not a share of milliseconds' wall time) plus the orphans'; with a
  // colorProgram, the wall time of the pass after the mesh.
  double colorMilliseconds = 0.0;
};

struct PolygonizeResult {
  TriangleMesh mesh;
  PolygonizeStats stats;
  bool cancelled = false;
};

Result<PolygonizeGrid> polygonizeGrid(const FieldProgram& program, const PolygonizeSettings& settings);

// One grid for frames polygonised in order with a PolygonizeHistory (a bake): add each frame, then
// grid() covers the grid polygonizeGrid gives every frame alone, with the finest of their cells.
class SequenceGrid {
 public:
  // Errors: polygonizeGrid's for this frame.
  Status add(const FieldProgram& frame, const PolygonizeSettings& settings);
  // nullopt while no frame with an inside was added.
  std::optional<PolygonizeGrid> grid() const;

 private:
  Bounds box_;
  float cellSize_ = 0.0f;
};

// For scrubbing with a history: the grid the history's previous frame was polygonised on when the
// grid `own` this frame would get alone lies inside it and its cells are at most `coarser` times
// `own`'s; otherwise `own`. A preview that moves little then stays on one grid, so blocks can be reused.
// A shape that moved out of it while the cell size holds keeps its lattice (holdScrubbingGrid with
// whole superblocks of 32 cells): the grid's origin moves by whole superblocks, its extent follows
// the shape, and the history keeps the blocks both grids share (off both grids' boundaries).
PolygonizeGrid scrubbingGrid(const PolygonizeGrid& own, const PolygonizeHistory& history, float coarser = 1.25f);

// Polygonises f = 0 of the program. Errors: bad resolution, an unbounded
// field without a bounds override, or empty/invalid bounds.
Result<PolygonizeResult> polygonize(const FieldProgram& program, const PolygonizeSettings& settings);

}  // namespace animorph
