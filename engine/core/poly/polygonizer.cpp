#include "core/poly/polygonizer.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>
#include <limits>
#include <mutex>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/field/surface_color.h"
#include "core/poly/marching_cubes_table.h"
#include "core/poly/polygonize_stage_times.h"
#include "core/poly/program_change.h"
#include "core/poly/scrubbing_grid.h"
#include "core/poly/sub_block_tests.h"

namespace animorph {

namespace {

constexpr int kBlock = 8;        // cells per block side
constexpr int kSuper = 4;        // blocks per superblock side
constexpr float kSnap = 1e-3f;   // edge parameter kept in [kSnap, 1 - kSnap]: no degenerate triangles
constexpr uint64_t kExternal = uint64_t(1) << 63;

struct Grid {
  glm::vec3 origin{0.0f};
  float h = 1.0f;
  int n[3] = {1, 1, 1};   // cells per axis
  int nb[3] = {1, 1, 1};  // blocks per axis
  int ns[3] = {1, 1, 1};  // superblocks per axis
};

struct ExternalVertex {
  int gi, gj, gk;  // base corner of the edge
  int axis;
  glm::vec3 position;
};

struct BlockOutput {
  std::vector<glm::vec3> positions, normals;
  // With per-block colours (PolygonizeRun::colorProg): one per position, made in the block's thread
  // with its programs; kept with the output by a history (coloured again when a colour changed).
  std::vector<glm::vec4> colors;
  std::vector<int32_t> ownedSlot;   // (lk*8 + lj)*8 + li)*3 + axis -> local vertex
  std::vector<uint64_t> corners;    // triangle corners: local index, or kExternal | external index
  std::vector<ExternalVertex> externals;
  size_t vertexOffset = 0, indexOffset = 0;
};

struct Scratch {
  FieldEvaluator evaluator;
  ActiveProgram active;
  std::vector<uint32_t> reaching;
  std::vector<float> x, y, z, v, e, gx, gy, gz;
  std::vector<int32_t> slot;
  // Per 4^3 sub-block programs, for blocks reached by many primitives (particles).
  ActiveProgram subActive[8];
  std::vector<uint32_t> subReaching;
  std::vector<uint8_t> vertexSub;   // sub-block of each owned vertex
  std::vector<uint32_t> previousReaching, merged;  // tolerance reuse: the previous frame's list, the union
  std::vector<uint32_t> gather;     // vertices of one sub-block
  SurfaceColorEvaluator color;      // the vertices' colours (per-block colours)
  std::vector<glm::vec4> rgba;
};

// A block reached by more primitives than this that the evaluator cannot skip evaluates each 4^3
// sub-block with only the primitives reaching it (the same values: the others add exact zeros).
constexpr size_t kSubSpecialise = 48;

// Primitives of prog that the evaluator does not skip against the box of a run of points
// (field_program_evaluate.cpp skips skeletal primitives -- points, particles -- whose reach misses
// it): per-sub-block lists prune only these. For skeletal ones the block's corners and vertices,
// evaluated one sub-block at a time, get the same pruning without the lists' cost (listing and
// specialising 8 programs, the sub-blocks' shared faces evaluated twice).
size_t unskippedCount(const ActiveProgram& prog) {
  size_t n = 0;
  for (const FieldOp& op : prog.ops)
    if (op.code == OpCode::Prims && op.primClass != PrimClass::Skeletal) n += op.count;
  return n;
}

enum class SuperState : uint8_t { Culled, Partial };

glm::vec3 outwardNormal(float gx, float gy, float gz, const glm::vec3& fallback) {
  glm::vec3 g(gx, gy, gz);
  float l = glm::length(g);
  if (!(l > 1e-20f) || !std::isfinite(l)) return fallback;
  return -g / l;
}

// What temporal coherence with a tolerance needs of an evaluated block (see
// PolygonizeSettings::reuseToleranceCells): its output stays right while the field moved by less
// than minAbs at every corner (no sign flips) and by little against minGap on its vertices' edges.
struct BlockSummary {
  float minAbs = 0.0f;   // smallest |f| over the evaluated corners off the grid boundary
  float minGap = std::numeric_limits<float>::infinity();  // smallest |f0 - f1| over its own vertices' edges
  float drift = 0.0f;    // bound on how far the field moved since the output was made
  uint8_t subLive = 0;   // live 4^3 sub-blocks, one bit each
  bool valid = false;
};

// A block's output may be kept when the field moved by at most `delta` since it was made: no
// corner changes sign, and each vertex t = f0 / (f0 - f1) moves by at most delta / (G - 2 delta)
// of its edge (G = |f0 - f1|), which must stay within `tolerance` cells.
bool keepsBlock(const BlockSummary& b, double delta, float tolerance, float T) {
  const double safety = 1e-5 * double(T);  // float rounding of the evaluations
  if (!(delta + safety < double(b.minAbs))) return false;
  if (std::isinf(b.minGap)) return true;
  return delta + safety <= double(tolerance) * double(b.minGap) / (1.0 + 2.0 * double(tolerance));
}

// The block's first nv vertices gathered sub-block by sub-block (sc.gather: vertex indices, each
// 4^3 sub-block's in turn) and their positions into sc.x / y / z in that order (sized >= nv).
void gatherBySubBlock(const BlockOutput& o, Scratch& sc, size_t nv) {
  sc.gather.clear();
  for (int sq = 0; sq < 8; ++sq)
    for (size_t q = 0; q < nv; ++q)
      if (sc.vertexSub[q] == sq) sc.gather.push_back(uint32_t(q));
  for (size_t q = 0; q < nv; ++q) {
    const glm::vec3& pq = o.positions[sc.gather[q]];
    sc.x[q] = pq.x;
    sc.y[q] = pq.y;
    sc.z[q] = pq.z;
  }
}

std::atomic<uint64_t> gSubBlockTestsSkipped{0};
std::atomic<bool> gSubBlockTestSkipping{true};

// A block's 4^3 sub-blocks are interval-tested in turn until this many in a row proved nothing (no
// sub-block culled yet); the rest are then taken as live untested. Each test walks the block's
// program once, about half the cost of evaluating the sub-block's corners, and on dense content a
// block that its own interval could not cull rarely has a sub-block that one can: in the
// animorphosis demo's C(t) at 96^3 (2.8, 4.0 and 5.2 s) the eight tests of each evaluated block
// culled none. Taking a sub-block as live never changes the mesh: one whose interval proves one
// sign has corners of that sign only, so no triangle (tests/core/polygonizer_sub_block_tests.cpp).
constexpr int kSubTestsWithoutCull = 2;

}  // namespace

uint64_t subBlockTestsSkippedTotal() { return gSubBlockTestsSkipped.load(std::memory_order_relaxed); }
void setSubBlockTestSkipping(bool enabled) { gSubBlockTestSkipping.store(enabled, std::memory_order_relaxed); }

struct PolygonizeHistory::State {
  glm::vec3 origin{0.0f};
  float h = 0.0f;
  int n[3] = {0, 0, 0};
  bool subBlockLists = true;
  bool colors = false;  // the outputs carry per-block colours
  FieldProgram program;
  std::vector<std::vector<uint32_t>> superCandidates;
  std::vector<std::unique_ptr<BlockOutput>> out;  // null: the block was culled
  std::vector<BlockSummary> summary;               // per block (valid for evaluated blocks)
};

PolygonizeHistory::PolygonizeHistory() = default;
PolygonizeHistory::~PolygonizeHistory() = default;
void PolygonizeHistory::clear() { state_.reset(); }

struct PolygonizeHistoryAccess {
  static std::unique_ptr<PolygonizeHistory::State>& state(PolygonizeHistory& h) { return h.state_; }
};

std::optional<PolygonizeGrid> PolygonizeHistory::grid() const {
  if (!state_) return std::nullopt;
  PolygonizeGrid g;
  g.origin = state_->origin;
  g.cellSize = state_->h;
  for (int a = 0; a < 3; ++a) g.cells[a] = state_->n[a];
  return g;
}

namespace {
Bounds gridBox(const PolygonizeGrid& g) {
  Bounds b;
  b.add(g.origin);
  b.add(g.origin + g.cellSize * glm::vec3(float(g.cells[0]), float(g.cells[1]), float(g.cells[2])));
  return b;
}
}  // namespace

Status SequenceGrid::add(const FieldProgram& frame, const PolygonizeSettings& settings) {
  auto g = polygonizeGrid(frame, settings);
  if (!g) return Error{g.error()};
  if (g->empty) return {};
  box_.add(gridBox(*g));
  cellSize_ = cellSize_ > 0.0f ? std::min(cellSize_, g->cellSize) : g->cellSize;
  return {};
}

std::optional<PolygonizeGrid> SequenceGrid::grid() const {
  if (!(cellSize_ > 0.0f)) return std::nullopt;
  PolygonizeGrid g;
  g.cellSize = cellSize_;
  for (int a = 0; a < 3; ++a) g.cells[a] = std::clamp(int(std::ceil(box_.size()[a] / cellSize_ - 1e-4f)), 1, 2048);
  g.origin = box_.min;
  return g;
}

PolygonizeGrid scrubbingGrid(const PolygonizeGrid& own, const PolygonizeHistory& history, float coarser) {
  return holdScrubbingGrid(own, history.grid(), coarser, kSuper * kBlock);
}

Result<PolygonizeGrid> polygonizeGrid(const FieldProgram& program, const PolygonizeSettings& s) {
  if (s.grid) {
    const PolygonizeGrid& g = *s.grid;
    bool ok = g.cellSize > 0.0f && std::isfinite(g.cellSize) && std::isfinite(g.origin.x) &&
              std::isfinite(g.origin.y) && std::isfinite(g.origin.z);
    for (int a = 0; a < 3; ++a) ok = ok && g.cells[a] >= 1 && g.cells[a] <= 2048;
    if (!ok) return Error{"polygonize: the grid override has no cells, a cell size <= 0 or a non-finite origin"};
    PolygonizeGrid r = g;
    r.empty = false;
    return r;
  }
  if (s.resolution < 2 || s.resolution > 2048)
    return Error{"polygonize: resolution " + std::to_string(s.resolution) + " is out of range (2..2048)"};
  PolygonizeGrid g;
  Bounds box;
  if (s.bounds) {
    box = *s.bounds;
    if (box.empty() || !std::isfinite(box.diagonal()) || box.diagonal() <= 0.0f)
      return Error{"polygonize: the bounds override is empty or not finite"};
    float L = std::max({box.size().x, box.size().y, box.size().z});
    g.cellSize = L / float(s.resolution);
    for (int a = 0; a < 3; ++a) g.cells[a] = std::max(1, int(std::lround(box.size()[a] / g.cellSize)));
  } else {
    if (program.unbounded())
      return Error{"polygonize: the field is inside everywhere far from its primitives (unbounded); give bounds"};
    box = program.tightBounds();
    if (box.empty()) {
      g.empty = true;
      return g;
    }
    float L = std::max({box.size().x, box.size().y, box.size().z, 1e-6f});
    float margin = std::max(0.0f, s.marginCells);
    float usable = float(s.resolution) - 2.0f * margin;
    g.cellSize = usable >= 1.0f ? L / usable : L / float(s.resolution);
    for (int a = 0; a < 3; ++a)
      g.cells[a] = std::clamp(int(std::ceil(box.size()[a] / g.cellSize + 2.0f * margin)), 1, s.resolution);
  }
  g.origin = box.center() - 0.5f * g.cellSize * glm::vec3(float(g.cells[0]), float(g.cells[1]), float(g.cells[2]));
  return g;
}

namespace {

constexpr int kPair = 2;  // blocks per pair side (the middle culling level)
constexpr uint32_t kUnresolved = 0xffffffffu;
// Pair culling on this thread (setPolygonizePairCulling; off only to measure and test against).
thread_local bool pairCullingOn = true;

// Sub-block (0..7) of a block-local cell.
inline int subOf(int i, int j, int k) {
  return (i >= kBlock / 2 ? 1 : 0) | (j >= kBlock / 2 ? 2 : 0) | (k >= kBlock / 2 ? 4 : 0);
}

// One block of one run: where it lies, which of its 4^3 sub-blocks may hold surface and the program
// its corners and vertices are evaluated with.
struct BlockJob {
  size_t bi = 0;
  int b[3] = {0, 0, 0};     // block index per axis
  int c0[3] = {0, 0, 0};    // first cell per axis
  int cnt[3] = {0, 0, 0};   // cells per axis (kBlock, or fewer at the grid's far side)
  const ActiveProgram* prog = nullptr;
  // Sub-blocks of 4^3 cells whose cells may hold surface (all of them without culling).
  bool subLive[8] = {true, true, true, true, true, true, true, true};
  bool perSub = false;      // each live sub-block has its own program (Scratch::subActive)
  int subLo[8][3], subHi[8][3];  // corner ranges (inclusive) of each sub-block, block-local
  int cx = 0, cy = 0, cz = 0;    // corners per axis (cells + 1)
  float val(const Scratch& sc, int i, int j, int k) const { return sc.v[size_t((k * cy + j) * cx + i)]; }
};

// The state one polygonize() call shares between its stages and worker threads: the grid, the
// culling levels' verdicts and candidate lists, the blocks' outputs, the counters of its stats.
// Each stage is a member function; they run in the order polygonize() calls them.
struct PolygonizeRun {
  PolygonizeRun(const FieldProgram& program, const PolygonizeSettings& s, const PolygonizeGrid& grid)
      : program(program), s(s), T(program.threshold), table(marchingCubesTable()) {
    g.origin = grid.origin;
    g.h = grid.cellSize;
    for (int a = 0; a < 3; ++a) g.n[a] = grid.cells[a];
    for (int a = 0; a < 3; ++a) {
      g.nb[a] = (g.n[a] + kBlock - 1) / kBlock;
      g.ns[a] = (g.nb[a] + kSuper - 1) / kSuper;
    }
    nBlocks = size_t(g.nb[0]) * g.nb[1] * g.nb[2];
    nSupers = size_t(g.ns[0]) * g.ns[1] * g.ns[2];
    margin = 1e-3f * T + 1e-7f;
    // Colours of the polygonised program itself are made per block; another colour program's
    // after the mesh (its primitives are not the blocks' ones).
    if (s.colors && (!s.colorProgram || s.colorProgram == &program)) colorProg = std::make_unique<ColorProgram>(program);
  }

  const FieldProgram& program;
  const PolygonizeSettings& s;
  const float T;
  const MarchingCubesTable& table;
  Grid g;
  size_t nBlocks = 0, nSupers = 0;
  float margin = 0.0f;  // |f| within which an interval proves no sign
  std::unique_ptr<ColorProgram> colorProg;  // per-block colours (settings.colors on the program itself)

  // Temporal coherence: the previous frame, when its grid and program structure match this one.
  std::unique_ptr<PolygonizeHistory::State> previous;
  std::vector<uint8_t> changed;      // per primitive, against the previous frame (its colour too, with colorProg)
  std::vector<uint8_t> colorChanged; // per primitive, with colorProg: its colour changed
  float tolerance = 0.0f;
  std::vector<float> changeBound;    // per primitive: how far its change can move the field
  std::vector<BlockSummary> summary;
  std::vector<uint8_t> superReused;  // superblocks whose primitives, this frame and the last, are all unchanged

  ActiveProgram allPrims;
  std::vector<SuperState> superState;
  std::vector<std::vector<uint32_t>> superCandidates;
  int np2[3] = {1, 1, 1};  // pairs per axis
  size_t nPairs = 0;
  std::vector<std::vector<uint32_t>> pairCandidates;
  // Per pair: its interval over the pair's box proves one sign (cullPairs): its blocks are culled
  // without testing each (the fine level's tests then grow with the surface, not the volume).
  std::vector<uint8_t> pairCulled;

  // Outputs only for blocks that are evaluated (most are culled at high resolution).
  std::vector<std::unique_ptr<BlockOutput>> out;
  std::atomic<size_t> culled{0}, evaluated{0}, cells{0}, points{0}, pairs{0}, done{0}, reused{0};
  std::atomic<int64_t> colorNs{0};  // the blocks' colour work, summed over threads

  glm::vec3 cornerPos(int i, int j, int k) const { return g.origin + g.h * glm::vec3(float(i), float(j), float(k)); }
  // World box of the corners of cells [c0, c0 + count) per axis.
  Bounds regionBox(const int c0[3], const int count[3]) const {
    Bounds b;
    b.add(cornerPos(c0[0], c0[1], c0[2]));
    b.add(cornerPos(c0[0] + count[0], c0[1] + count[1], c0[2] + count[2]));
    return b;
  }
  bool touchesBoundary(const int c0[3], const int count[3]) const {
    for (int a = 0; a < 3; ++a)
      if (c0[a] == 0 || c0[a] + count[a] >= g.n[a]) return true;
    return false;
  }
  // True when the interval proves one sign over the region (and the grid
  // boundary, forced outside, cannot create a surface there).
  bool oneSigned(const Interval& iv, bool boundary) const {
    if (iv.hi < -margin) return true;
    if (iv.lo > margin && !boundary) return true;
    return false;
  }
  bool onGridBoundary(int gi, int gj, int gk) const {
    return gi == 0 || gj == 0 || gk == 0 || gi == g.n[0] || gj == g.n[1] || gk == g.n[2];
  }
  size_t superOfBlock(const int b[3]) const {
    return size_t(b[0] / kSuper) + size_t(g.ns[0]) * (size_t(b[1] / kSuper) + size_t(g.ns[1]) * size_t(b[2] / kSuper));
  }

  void takeHistory();
  bool remapShiftedHistory();
  // Per superblock, after remapShiftedHistory: its previous lists may skip it whole (superReused).
  std::vector<uint8_t> superKeepable;
  void cullSuperblocks(tbb::task_arena& arena, tbb::enumerable_thread_specific<Scratch>& scratch);
  void listPairCandidates(tbb::task_arena& arena);
  void cullPairs(tbb::task_arena& arena, tbb::enumerable_thread_specific<Scratch>& scratch);
  size_t pairOfBlock(const int b[3]) const {
    return size_t(b[0] / kPair) + size_t(np2[0]) * (size_t(b[1] / kPair) + size_t(np2[1]) * size_t(b[2] / kPair));
  }
  size_t blocksOutsideFineLevel() const;
  bool runBlocks(tbb::task_arena& arena, tbb::enumerable_thread_specific<Scratch>& scratch);
  void processBlock(size_t bi, Scratch& sc);
  bool cullOrReuseBlock(BlockJob& job, Scratch& sc);
  bool reuseWithinTolerance(const BlockJob& job, Scratch& sc, size_t si, const Bounds& bb);
  void specialiseSubBlocks(BlockJob& job, Scratch& sc);
  void evaluateCorners(BlockJob& job, Scratch& sc);
  void evaluateCornersPerSub(const BlockJob& job, Scratch& sc);
  void evaluateCornersInRuns(const BlockJob& job, Scratch& sc, int np);
  void summariseCorners(const BlockJob& job, const Scratch& sc);
  void triangulateBlock(const BlockJob& job, Scratch& sc);
  void gradientNormals(const BlockJob& job, Scratch& sc);
  void normalsWithColors(const BlockJob& job, Scratch& sc);
  void colorVertices(const ActiveProgram& active, BlockOutput& o, Scratch& sc, size_t m);
  void recolorKept(BlockOutput& o, Scratch& sc);
  void markColorChanges();
  void stitch(tbb::task_arena& arena, TriangleMesh& mesh);
  size_t addOrphanVertices(TriangleMesh& mesh);
  void saveHistory();
};

void PolygonizeRun::takeHistory() {
  if (s.history) previous = std::move(PolygonizeHistoryAccess::state(*s.history));
  if (previous && s.culling &&
      (previous->origin != g.origin || previous->n[0] != g.n[0] || previous->n[1] != g.n[1] || previous->n[2] != g.n[2]))
    remapShiftedHistory();
  if (previous && s.culling && previous->subBlockLists == s.subBlockLists && previous->origin == g.origin &&
      previous->h == g.h && previous->n[0] == g.n[0] && previous->n[1] == g.n[1] && previous->n[2] == g.n[2] &&
      previous->out.size() == nBlocks && previous->superCandidates.size() == nSupers &&
      previous->colors == (colorProg != nullptr) && sameStructure(program, previous->program))
    changed = changedPrimitives(program, previous->program);
  else
    previous.reset();
  if (previous && colorProg) markColorChanges();
  tolerance = std::max(0.0f, s.reuseToleranceCells);
  if (previous && tolerance > 0.0f) changeBound = primitiveChangeBounds(program, previous->program);
  summary.resize(nBlocks);
  superReused.assign(nSupers, 0);
}

// Temporal coherence on a grid that moved by whole superblocks on the previous frame's lattice
// (holdScrubbingGrid with latticeCells = kSuper * kBlock): the previous frame's superblock lists,
// block outputs and summaries moved to this grid's indices, the outputs' external edges to its
// cells. A block's output is kept only where, on each axis, the grid did not change or the block
// lies whole inside both grids off both grids' boundaries (the boundary is forced outside: such a
// block's output depends on the grid); a superblock is skipped whole (superKeepable) only under
// the same condition. False when this
// grid is not such a shift of the previous one (previous left as it was: a full sweep).
bool PolygonizeRun::remapShiftedHistory() {
  PolygonizeHistory::State& p = *previous;
  constexpr int kSuperCells = kSuper * kBlock;
  if (p.h != g.h) return false;
  int shift[3], pnb[3], pns[3];  // shift: this grid's cell index of the previous grid's cell 0
  size_t oldBlocks = 1, oldSupers = 1;
  for (int a = 0; a < 3; ++a) {
    const float moved = (p.origin[a] - g.origin[a]) / g.h;
    shift[a] = int(std::lround(moved));
    if (std::fabs(moved - float(shift[a])) > 1e-2f || shift[a] % kSuperCells != 0) return false;
    pnb[a] = (p.n[a] + kBlock - 1) / kBlock;
    pns[a] = (pnb[a] + kSuper - 1) / kSuper;
    oldBlocks *= size_t(pnb[a]);
    oldSupers *= size_t(pns[a]);
  }
  if (p.out.size() != oldBlocks || p.superCandidates.size() != oldSupers || p.summary.size() != oldBlocks) return false;
  // Whether cells [c0, c0 + count) of an axis lie whole and off the boundary of n cells.
  auto inside = [](int c0, int count, int n) { return c0 > 0 && c0 + count < n; };
  // An axis on which the grid did not change: its blocks are the same whether on a boundary or not.
  bool same[3];
  for (int a = 0; a < 3; ++a) same[a] = shift[a] == 0 && p.n[a] == g.n[a];
  std::vector<std::unique_ptr<BlockOutput>> out2(nBlocks);
  std::vector<BlockSummary> summary2(nBlocks);
  for (size_t bi = 0; bi < nBlocks; ++bi) {
    const int b[3] = {int(bi % size_t(g.nb[0])), int((bi / size_t(g.nb[0])) % size_t(g.nb[1])),
                      int(bi / (size_t(g.nb[0]) * g.nb[1]))};
    bool keep = true;
    size_t old = 0;
    for (int a = 2; a >= 0 && keep; --a) {
      const int c0 = b[a] * kBlock, c0Old = c0 - shift[a];
      keep = same[a] || (inside(c0, kBlock, g.n[a]) && inside(c0Old, kBlock, p.n[a]));
      old = old * size_t(pnb[a]) + size_t(keep ? c0Old / kBlock : 0);
    }
    if (!keep || !p.out[old]) continue;
    for (ExternalVertex& ev : p.out[old]->externals) {
      ev.gi += shift[0];
      ev.gj += shift[1];
      ev.gk += shift[2];
    }
    out2[bi] = std::move(p.out[old]);
    summary2[bi] = p.summary[old];
  }
  std::vector<std::vector<uint32_t>> supers2(nSupers);
  superKeepable.assign(nSupers, 0);
  for (size_t si = 0; si < nSupers; ++si) {
    const int sidx[3] = {int(si % size_t(g.ns[0])), int((si / size_t(g.ns[0])) % size_t(g.ns[1])),
                         int(si / (size_t(g.ns[0]) * g.ns[1]))};
    bool mapped = true, whole = true;
    size_t old = 0;
    for (int a = 2; a >= 0 && mapped; --a) {
      const int c0 = sidx[a] * kSuperCells, c0Old = c0 - shift[a];
      mapped = c0Old >= 0 && c0Old < p.n[a];
      whole = whole && (same[a] || (inside(c0, kSuperCells, g.n[a]) && inside(c0Old, kSuperCells, p.n[a])));
      old = old * size_t(pns[a]) + size_t(mapped ? c0Old / kSuperCells : 0);
    }
    if (!mapped) continue;
    supers2[si] = std::move(p.superCandidates[old]);
    superKeepable[si] = whole;
  }
  p.origin = g.origin;
  for (int a = 0; a < 3; ++a) p.n[a] = g.n[a];
  p.out = std::move(out2);
  p.summary = std::move(summary2);
  p.superCandidates = std::move(supers2);
  return true;
}

// With per-block colours: primitives whose colour changed since the previous frame. Such a change
// alone leaves the field as it was: a block it reaches is not kept whole (changed), and one kept
// within the tolerance is coloured again.
void PolygonizeRun::markColorChanges() {
  colorChanged.assign(program.primitiveCount(), 0);
  for (const FieldOp& op : program.ops) {
    if (op.code != OpCode::Prims) continue;
    for (uint32_t k = 0; k < op.count; ++k) {
      const uint32_t g = op.primBegin + k;
      if (g >= colorChanged.size()) break;
      colorChanged[g] =
          program.primitiveColor(op.primClass, op.first + k) != previous->program.primitiveColor(op.primClass, op.first + k);
      changed[g] = uint8_t(changed[g] | colorChanged[g]);
    }
  }
}

// Coarse level: superblocks whose interval proves one sign are culled; each keeps the primitives
// reaching it.
void PolygonizeRun::cullSuperblocks(tbb::task_arena& arena, tbb::enumerable_thread_specific<Scratch>& scratch) {
  superState.assign(nSupers, SuperState::Partial);
  superCandidates.resize(nSupers);
  if (!s.culling) return;
  arena.execute([&] {
    tbb::parallel_for(size_t(0), nSupers, [&](size_t si) {
      Scratch& sc = scratch.local();
      int sidx[3] = {int(si % size_t(g.ns[0])), int((si / size_t(g.ns[0])) % size_t(g.ns[1])),
                     int(si / (size_t(g.ns[0]) * g.ns[1]))};
      int c0[3], cnt[3];
      for (int a = 0; a < 3; ++a) {
        c0[a] = sidx[a] * kSuper * kBlock;
        cnt[a] = std::min(kSuper * kBlock, g.n[a] - c0[a]);
      }
      Bounds b = regionBox(c0, cnt);
      program.primitivesReaching(b, superCandidates[si]);
      if (previous) {
        auto unchanged = [&](const std::vector<uint32_t>& list) {
          for (uint32_t p : list)
            if (changed[p]) return false;
          return true;
        };
        superReused[si] = unchanged(superCandidates[si]) && unchanged(previous->superCandidates[si]) &&
                          (superKeepable.empty() || superKeepable[si]);
      }
      program.specialise(superCandidates[si], sc.active);
      Interval iv = program.interval(sc.active, b.center(), 0.5f * b.diagonal());
      if (oneSigned(iv, touchesBoundary(c0, cnt))) superState[si] = SuperState::Culled;
    });
  });
}

// Middle level: pairs of blocks per axis (2x2x2 blocks, inside one superblock), each with its
// superblock's candidates whose box overlaps its box. A block's box lies inside its pair's (the
// same grid corners), so every primitive reaching the block is in that list and the block tests
// only those (the same list as testing the superblock's).
void PolygonizeRun::listPairCandidates(tbb::task_arena& arena) {
  for (int a = 0; a < 3; ++a) np2[a] = (g.nb[a] + kPair - 1) / kPair;
  nPairs = size_t(np2[0]) * np2[1] * np2[2];
  pairCandidates.resize(s.culling ? nPairs : 0);
  if (!s.culling) return;
  arena.execute([&] {
    tbb::parallel_for(size_t(0), nPairs, [&](size_t pi) {
      int pidx[3] = {int(pi % size_t(np2[0])), int((pi / size_t(np2[0])) % size_t(np2[1])),
                     int(pi / (size_t(np2[0]) * np2[1]))};
      size_t si = size_t(pidx[0] * kPair / kSuper) +
                  size_t(g.ns[0]) * (size_t(pidx[1] * kPair / kSuper) + size_t(g.ns[1]) * size_t(pidx[2] * kPair / kSuper));
      if (superState[si] == SuperState::Culled || superReused[si]) return;
      int c0[3], cnt[3];
      for (int a = 0; a < 3; ++a) {
        c0[a] = pidx[a] * kPair * kBlock;
        cnt[a] = std::min(kPair * kBlock, g.n[a] - c0[a]);
      }
      const Bounds pb = regionBox(c0, cnt);
      for (uint32_t p : superCandidates[si]) {
        const Bounds& box = program.primitiveBounds[p].box;
        if (!(box.min.x > pb.max.x || box.max.x < pb.min.x || box.min.y > pb.max.y || box.max.y < pb.min.y ||
              box.min.z > pb.max.z || box.max.z < pb.min.z))
          pairCandidates[pi].push_back(p);
      }
    });
  });
}

// Middle level's culling: a pair (2x2x2 blocks) whose interval over its box, with its candidates,
// proves one sign is culled whole, as a superblock is. Its blocks' own intervals would each have
// had to prove it too, or they were evaluated and found no sign change (their corners lie in the
// pair's box): either way no triangles and no vertices, so the mesh is the same, while the blocks
// tested one by one are those near the surface only (about 4x, not 8x, at twice the resolution).
void PolygonizeRun::cullPairs(tbb::task_arena& arena, tbb::enumerable_thread_specific<Scratch>& scratch) {
  pairCulled.assign(s.culling && pairCullingOn ? nPairs : 0, 0);
  if (pairCulled.empty()) return;
  arena.execute([&] {
    tbb::parallel_for(size_t(0), nPairs, [&](size_t pi) {
      int pidx[3] = {int(pi % size_t(np2[0])), int((pi / size_t(np2[0])) % size_t(np2[1])),
                     int(pi / (size_t(np2[0]) * np2[1]))};
      const int b0[3] = {pidx[0] * kPair, pidx[1] * kPair, pidx[2] * kPair};
      const size_t si = superOfBlock(b0);
      if (superState[si] == SuperState::Culled || superReused[si]) return;
      int c0[3], cnt[3];
      for (int a = 0; a < 3; ++a) {
        c0[a] = pidx[a] * kPair * kBlock;
        cnt[a] = std::min(kPair * kBlock, g.n[a] - c0[a]);
      }
      Scratch& sc = scratch.local();
      const Bounds pb = regionBox(c0, cnt);
      program.specialise(pairCandidates[pi], sc.active);
      const Interval iv = program.interval(sc.active, pb.center(), 0.5f * pb.diagonal());
      if (oneSigned(iv, touchesBoundary(c0, cnt))) pairCulled[pi] = 1;
    });
  });
}

// Blocks the fine level does not test one by one: those of culled or reused superblocks and of
// culled pairs (measuring: PolygonizeStageTimes::blocksVisited).
size_t PolygonizeRun::blocksOutsideFineLevel() const {
  size_t n = 0;
  for (size_t bi = 0; bi < nBlocks; ++bi) {
    const int b[3] = {int(bi % size_t(g.nb[0])), int((bi / size_t(g.nb[0])) % size_t(g.nb[1])),
                      int(bi / (size_t(g.nb[0]) * g.nb[1]))};
    const size_t si = superOfBlock(b);
    if (superState[si] == SuperState::Culled || superReused[si] || (!pairCulled.empty() && pairCulled[pairOfBlock(b)]))
      ++n;
  }
  return n;
}

// Fine level: every block, in parallel, with progress and cancel. Returns false when cancelled.
bool PolygonizeRun::runBlocks(tbb::task_arena& arena, tbb::enumerable_thread_specific<Scratch>& scratch) {
  out.resize(nBlocks);
  std::mutex progressMutex;
  size_t reported = 0;
  std::atomic<bool> cancelled{false};
  const size_t reportEvery = std::max<size_t>(1, nBlocks / 100);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nBlocks, 4), [&](const tbb::blocked_range<size_t>& r) {
      Scratch& sc = scratch.local();
      for (size_t bi = r.begin(); bi != r.end(); ++bi) {
        if (s.cancel && s.cancel->load(std::memory_order_relaxed)) {
          cancelled.store(true);
          return;
        }
        processBlock(bi, sc);
        size_t d = done.fetch_add(1, std::memory_order_relaxed) + 1;
        if (s.progress && (d % reportEvery == 0 || d == nBlocks)) {
          std::lock_guard<std::mutex> lock(progressMutex);
          if (d > reported) {  // blocks finish out of order: report only forward
            reported = d;
            s.progress(0.95f * float(d) / float(nBlocks));
          }
        }
      }
    });
  });
  return !(cancelled.load() || (s.cancel && s.cancel->load()));
}

void PolygonizeRun::processBlock(size_t bi, Scratch& sc) {
  BlockJob job;
  job.bi = bi;
  job.b[0] = int(bi % size_t(g.nb[0]));
  job.b[1] = int((bi / size_t(g.nb[0])) % size_t(g.nb[1]));
  job.b[2] = int(bi / (size_t(g.nb[0]) * g.nb[1]));
  for (int a = 0; a < 3; ++a) {
    job.c0[a] = job.b[a] * kBlock;
    job.cnt[a] = std::min(kBlock, g.n[a] - job.c0[a]);
  }
  job.prog = &allPrims;
  if (s.culling && cullOrReuseBlock(job, sc)) return;
  specialiseSubBlocks(job, sc);
  evaluated.fetch_add(1, std::memory_order_relaxed);
  evaluateCorners(job, sc);
  if (s.culling) summariseCorners(job, sc);
  triangulateBlock(job, sc);
  gradientNormals(job, sc);
}

// Culling of one block: true when it is done (culled by its superblock or its own interval, or
// its previous output kept). Otherwise leaves its specialised program and live sub-blocks in job.
bool PolygonizeRun::cullOrReuseBlock(BlockJob& job, Scratch& sc) {
  const size_t bi = job.bi;
  const size_t si = superOfBlock(job.b);
  if (superState[si] == SuperState::Culled) {
    culled.fetch_add(1, std::memory_order_relaxed);
    return true;
  }
  if (superReused[si]) {
    // Same primitives reaching it, same data: the previous frame's output (null: culled).
    out[bi] = std::move(previous->out[bi]);
    if (previous->summary.size() == nBlocks) summary[bi] = previous->summary[bi];
    (out[bi] ? evaluated : culled).fetch_add(1, std::memory_order_relaxed);
    reused.fetch_add(1, std::memory_order_relaxed);
    return true;
  }
  const size_t pi = pairOfBlock(job.b);
  if (!pairCulled.empty() && pairCulled[pi]) {
    culled.fetch_add(1, std::memory_order_relaxed);
    return true;
  }
  Bounds bb = regionBox(job.c0, job.cnt);
  program.primitivesReaching(bb, sc.reaching, &pairCandidates[pi]);
  program.specialise(sc.reaching, sc.active);
  Interval iv = program.interval(sc.active, bb.center(), 0.5f * bb.diagonal());
  if (oneSigned(iv, touchesBoundary(job.c0, job.cnt))) {
    culled.fetch_add(1, std::memory_order_relaxed);
    return true;
  }
  job.prog = &sc.active;
  // Sub-blocks tested so far (kSubTestsWithoutCull); a negative count tests every one.
  int liveTested = gSubBlockTestSkipping.load(std::memory_order_relaxed) ? 0 : -8, culledTested = 0;
  for (int q = 0; q < 8; ++q) {
    int s0[3], sn[3];
    for (int a = 0; a < 3; ++a) {
      int half = ((q >> a) & 1) * (kBlock / 2);
      s0[a] = job.c0[a] + half;
      sn[a] = std::min(kBlock / 2, job.cnt[a] - half);
    }
    if (sn[0] <= 0 || sn[1] <= 0 || sn[2] <= 0) {
      job.subLive[q] = false;
    } else if (culledTested == 0 && liveTested >= kSubTestsWithoutCull) {
      job.subLive[q] = true;
      gSubBlockTestsSkipped.fetch_add(1, std::memory_order_relaxed);
    } else {
      Bounds sb = regionBox(s0, sn);
      job.subLive[q] =
          !oneSigned(program.interval(sc.active, sb.center(), 0.5f * sb.diagonal()), touchesBoundary(s0, sn));
      (job.subLive[q] ? liveTested : culledTested) += 1;
    }
  }
  uint8_t liveMask = 0;
  for (int q = 0; q < 8; ++q) liveMask |= uint8_t(job.subLive[q] ? 1 << q : 0);
  if (!changeBound.empty() && previous->out[bi] && previous->summary[bi].valid &&
      previous->summary[bi].subLive == liveMask && reuseWithinTolerance(job, sc, si, bb))
    return true;
  summary[bi].subLive = liveMask;
  return false;
}

// Tolerance reuse: the field moved here by at most the sum of the change bounds of the primitives
// reaching the block in either frame (the others add exact zeros in both). This frame's primitives
// alone already too much: no need to ask the previous program. True when the block's previous
// output is kept.
bool PolygonizeRun::reuseWithinTolerance(const BlockJob& job, Scratch& sc, size_t si, const Bounds& bb) {
  const size_t bi = job.bi;
  double delta = previous->summary[bi].drift;
  for (uint32_t p : sc.reaching) delta += double(changeBound[p]);
  if (keepsBlock(previous->summary[bi], delta, tolerance, T)) {
    previous->program.primitivesReaching(bb, sc.previousReaching, &previous->superCandidates[si]);
    delta = previous->summary[bi].drift;
    sc.merged.clear();
    std::set_union(sc.reaching.begin(), sc.reaching.end(), sc.previousReaching.begin(), sc.previousReaching.end(),
                   std::back_inserter(sc.merged));
    for (uint32_t p : sc.merged) delta += double(changeBound[p]);
  }
  if (!keepsBlock(previous->summary[bi], delta, tolerance, T)) return false;
  out[bi] = std::move(previous->out[bi]);
  if (colorProg)
    for (uint32_t p : sc.reaching)
      if (colorChanged[p]) {
        recolorKept(*out[bi], sc);
        break;
      }
  summary[bi] = previous->summary[bi];
  summary[bi].drift = float(delta);
  evaluated.fetch_add(1, std::memory_order_relaxed);
  reused.fetch_add(1, std::memory_order_relaxed);
  return true;
}

// The sub-blocks' corner ranges, and for a block reached by many primitives, a program per live
// sub-block with only the primitives reaching it.
void PolygonizeRun::specialiseSubBlocks(BlockJob& job, Scratch& sc) {
  job.perSub = s.culling && s.subBlockLists &&
               (s.subBlockListsForSkeletal ? job.prog->primitiveCount : unskippedCount(*job.prog)) > kSubSpecialise;
  for (int q = 0; q < 8; ++q)
    for (int a = 0; a < 3; ++a) {
      job.subLo[q][a] = ((q >> a) & 1) * (kBlock / 2);
      job.subHi[q][a] = std::min(job.subLo[q][a] + kBlock / 2, job.cnt[a]);
    }
  if (!job.perSub) return;
  for (int q = 0; q < 8; ++q) {
    if (!job.subLive[q]) continue;
    int s0[3], sn[3];
    for (int a = 0; a < 3; ++a) {
      s0[a] = job.c0[a] + job.subLo[q][a];
      sn[a] = job.subHi[q][a] - job.subLo[q][a];
    }
    program.primitivesReaching(regionBox(s0, sn), sc.subReaching, &sc.reaching);
    program.specialise(sc.subReaching, sc.subActive[q]);
  }
}

// Corner values of the block's cells (its own corners plus the +1 layer) into sc.v; only the
// corners of live sub-blocks are evaluated. The grid boundary counts as outside, so a surface cut
// by it is closed.
void PolygonizeRun::evaluateCorners(BlockJob& job, Scratch& sc) {
  job.cx = job.cnt[0] + 1;
  job.cy = job.cnt[1] + 1;
  job.cz = job.cnt[2] + 1;
  const int np = job.cx * job.cy * job.cz;
  size_t liveCells = 0;
  for (int k = 0; k < job.cnt[2]; ++k)
    for (int j = 0; j < job.cnt[1]; ++j)
      for (int i = 0; i < job.cnt[0]; ++i) liveCells += job.subLive[subOf(i, j, k)];
  cells.fetch_add(liveCells, std::memory_order_relaxed);
  sc.x.resize(size_t(np));
  sc.y.resize(size_t(np));
  sc.z.resize(size_t(np));
  sc.v.assign(size_t(np), 0.0f);
  if (job.perSub) evaluateCornersPerSub(job, sc);
  else evaluateCornersInRuns(job, sc, np);
  for (int k = 0, p = 0; k < job.cz; ++k)
    for (int j = 0; j < job.cy; ++j)
      for (int i = 0; i < job.cx; ++i, ++p)
        if (onGridBoundary(job.c0[0] + i, job.c0[1] + j, job.c0[2] + k))
          sc.v[size_t(p)] = std::min(sc.v[size_t(p)], -1e-6f * T);
}

// Each live sub-block's corners with its own program (shared faces twice, same values).
void PolygonizeRun::evaluateCornersPerSub(const BlockJob& job, Scratch& sc) {
  const int cx = job.cx, cy = job.cy;
  for (int q = 0; q < 8; ++q) {
    if (!job.subLive[q]) continue;
    const int* lo = job.subLo[q];
    const int* hi = job.subHi[q];
    int ne = 0;
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          glm::vec3 c = cornerPos(job.c0[0] + i, job.c0[1] + j, job.c0[2] + k);
          sc.x[size_t(ne)] = c.x;
          sc.y[size_t(ne)] = c.y;
          sc.z[size_t(ne)] = c.z;
          ++ne;
        }
    sc.e.resize(size_t(ne));
    sc.evaluator.evaluate(program, sc.subActive[q], sc.x.data(), sc.y.data(), sc.z.data(), ne, sc.e.data());
    points.fetch_add(size_t(ne), std::memory_order_relaxed);
    pairs.fetch_add(size_t(ne) * sc.subActive[q].primitiveCount, std::memory_order_relaxed);
    ne = 0;
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) sc.v[size_t((k * cy + j) * cx + i)] = sc.e[size_t(ne++)];
  }
}

// Corners of live sub-blocks (each spans its cells plus the +1 layer), numbered sub-block by
// sub-block and evaluated one sub-block at a time: a compact run of points lets the evaluator skip
// the map subtrees and primitives that reach the block but not that part.
void PolygonizeRun::evaluateCornersInRuns(const BlockJob& job, Scratch& sc, int np) {
  const int cx = job.cx, cy = job.cy;
  sc.slot.assign(size_t(np), -1);
  int ne = 0;
  int runStart[9];
  for (int q = 0; q < 8; ++q) {
    runStart[q] = ne;
    if (!job.subLive[q]) continue;
    for (int k = job.subLo[q][2]; k <= job.subHi[q][2]; ++k)
      for (int j = job.subLo[q][1]; j <= job.subHi[q][1]; ++j)
        for (int i = job.subLo[q][0]; i <= job.subHi[q][0]; ++i) {
          int& slot = sc.slot[size_t((k * cy + j) * cx + i)];
          if (slot >= 0) continue;
          glm::vec3 c = cornerPos(job.c0[0] + i, job.c0[1] + j, job.c0[2] + k);
          sc.x[size_t(ne)] = c.x;
          sc.y[size_t(ne)] = c.y;
          sc.z[size_t(ne)] = c.z;
          slot = ne++;
        }
  }
  runStart[8] = ne;
  sc.e.resize(size_t(ne));
  for (int q = 0; q < 8; ++q) {
    const int first = runStart[q], count = runStart[q + 1] - runStart[q];
    if (count > 0)
      sc.evaluator.evaluate(program, *job.prog, sc.x.data() + first, sc.y.data() + first, sc.z.data() + first, count,
                            sc.e.data() + first);
  }
  points.fetch_add(size_t(ne), std::memory_order_relaxed);
  pairs.fetch_add(size_t(ne) * job.prog->primitiveCount, std::memory_order_relaxed);
  for (int p = 0; p < np; ++p)
    if (sc.slot[size_t(p)] >= 0) sc.v[size_t(p)] = sc.e[size_t(sc.slot[size_t(p)])];
}

// For tolerance reuse in the next frame: the smallest |f| over the evaluated corners (those of live
// sub-blocks) off the grid boundary (forced outside there in every frame).
void PolygonizeRun::summariseCorners(const BlockJob& job, const Scratch& sc) {
  float minAbs = std::numeric_limits<float>::infinity();
  for (int q = 0; q < 8; ++q) {
    if (!job.subLive[q]) continue;
    for (int k = job.subLo[q][2]; k <= job.subHi[q][2]; ++k)
      for (int j = job.subLo[q][1]; j <= job.subHi[q][1]; ++j)
        for (int i = job.subLo[q][0]; i <= job.subHi[q][0]; ++i) {
          if (onGridBoundary(job.c0[0] + i, job.c0[1] + j, job.c0[2] + k)) continue;
          minAbs = std::min(minAbs, std::abs(job.val(sc, i, j, k)));
        }
  }
  summary[job.bi].minAbs = minAbs;
  summary[job.bi].valid = true;
}

// Builds one block's BlockOutput: a vertex per crossed edge it owns (its own corners' +x, +y, +z
// edges), the rest recorded as externals resolved by stitch().
struct BlockMesher {
  PolygonizeRun& run;
  const BlockJob& job;
  Scratch& sc;
  BlockOutput& o;
  BlockSummary& summary;

  uint64_t edgeVertex(int li, int lj, int lk, int axis, int cellSub) {
    int lj2 = lj + (axis == 1), li2 = li + (axis == 0), lk2 = lk + (axis == 2);
    float f0 = job.val(sc, li, lj, lk), f1 = job.val(sc, li2, lj2, lk2);
    float t = f0 / (f0 - f1);
    t = std::clamp(t, kSnap, 1.0f - kSnap);
    const int* c0 = job.c0;
    glm::vec3 p0 = run.cornerPos(c0[0] + li, c0[1] + lj, c0[2] + lk);
    glm::vec3 p1 = run.cornerPos(c0[0] + li2, c0[1] + lj2, c0[2] + lk2);
    glm::vec3 pos = p0 + t * (p1 - p0);
    if (li < kBlock && lj < kBlock && lk < kBlock) {
      if (o.ownedSlot.empty()) o.ownedSlot.assign(size_t(kBlock * kBlock * kBlock * 3), -1);
      int32_t& slot = o.ownedSlot[size_t(((lk * kBlock + lj) * kBlock + li) * 3 + axis)];
      if (slot < 0) {
        summary.minGap = std::min(summary.minGap, std::abs(f0 - f1));
        slot = int32_t(o.positions.size());
        o.positions.push_back(pos);
        sc.vertexSub.push_back(uint8_t(cellSub));
        // Fallback normal: along the edge, from the inside corner to the outside one.
        glm::vec3 dir = glm::normalize(p1 - p0);
        o.normals.push_back(f0 >= 0.0f ? dir : -dir);
      }
      return uint64_t(slot);
    }
    o.externals.push_back({c0[0] + li, c0[1] + lj, c0[2] + lk, axis, pos});
    return kExternal | uint64_t(o.externals.size() - 1);
  }

  void triangulate() {
    const MarchingCubesTable& table = run.table;
    sc.vertexSub.clear();
    for (int k = 0; k < job.cnt[2]; ++k)
      for (int j = 0; j < job.cnt[1]; ++j)
        for (int i = 0; i < job.cnt[0]; ++i) {
          const int cellSub = subOf(i, j, k);
          int mask = 0;
          for (int c = 0; c < 8; ++c)
            if (job.val(sc, i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)) >= 0.0f) mask |= 1 << c;
          if (mask == 0 || mask == 255 || !job.subLive[cellSub]) continue;
          const auto& tri = table.triangles[size_t(mask)];
          for (int q = 0; tri[size_t(q)] != 255; ++q) {
            int e = tri[size_t(q)];
            int cA = table.edgeCorners[size_t(e)][0];
            o.corners.push_back(edgeVertex(i + (cA & 1), j + ((cA >> 1) & 1), k + ((cA >> 2) & 1),
                                           table.edgeAxis[size_t(e)], cellSub));
          }
        }
  }
};

void PolygonizeRun::triangulateBlock(const BlockJob& job, Scratch& sc) {
  out[job.bi] = std::make_unique<BlockOutput>();
  BlockMesher mesher{*this, job, sc, *out[job.bi], summary[job.bi]};
  mesher.triangulate();
}

// Normals from the field gradient at the block's own vertices (and their colours, with per-block
// colours).
void PolygonizeRun::gradientNormals(const BlockJob& job, Scratch& sc) {
  BlockOutput& o = *out[job.bi];
  size_t nv = o.positions.size();
  if (nv == 0) return;
  if (colorProg && !job.perSub) {
    normalsWithColors(job, sc);
    return;
  }
  sc.x.resize(nv);
  sc.y.resize(nv);
  sc.z.resize(nv);
  sc.v.resize(nv);
  sc.gx.resize(nv);
  sc.gy.resize(nv);
  sc.gz.resize(nv);
  // Each sub-block's vertices in one run (a vertex lies on an edge of its cell), with its own
  // program, or the block's (the evaluator then skips the skeletal primitives missing the run).
  for (int sq = 0; sq < 8; ++sq) {
    sc.gather.clear();
    for (size_t q = 0; q < nv; ++q)
      if (sc.vertexSub[q] == sq) sc.gather.push_back(uint32_t(q));
    if (sc.gather.empty()) continue;
    size_t m = sc.gather.size();
    for (size_t q = 0; q < m; ++q) {
      const glm::vec3& pq = o.positions[sc.gather[q]];
      sc.x[q] = pq.x;
      sc.y[q] = pq.y;
      sc.z[q] = pq.z;
    }
    const ActiveProgram& active = job.perSub ? sc.subActive[sq] : *job.prog;
    sc.evaluator.evaluate(program, active, sc.x.data(), sc.y.data(), sc.z.data(), int(m), sc.v.data(), sc.gx.data(),
                          sc.gy.data(), sc.gz.data());
    for (size_t q = 0; q < m; ++q) {
      glm::vec3& nq = o.normals[sc.gather[q]];
      nq = outwardNormal(sc.gx[q], sc.gy[q], sc.gz[q], nq);
    }
    pairs.fetch_add(m * active.primitiveCount, std::memory_order_relaxed);
  }
  points.fetch_add(nv, std::memory_order_relaxed);
  if (!colorProg) return;
  // Colours (the sub-blocks' own programs gave the normals): every vertex with the block's program,
  // one walk per run of 128 (sub-block by sub-block, so each run stays compact), not one per sub-block.
  gatherBySubBlock(o, sc, nv);
  colorVertices(*job.prog, o, sc, nv);
}

// Normals and colours in one walk (field/surface_color.h, evaluateActiveWithGradient) where the
// block's vertices are evaluated with the block's program: one walk per sub-block's vertices, as
// the gradient walk without colours runs, instead of that walk and then the colour walk over the
// same ops at the same points. The gradients are the evaluator's over the same points, bit for
// bit, so the normals are those of a polygonisation without colours. Per sub-block, not per run of
// 128 of the block's vertices: a run's box skips fewer map subtrees than a sub-block's, and in the
// animorphosis demo the combined walk over whole blocks executed 17 % more instructions than a
// polygonisation without colours, per sub-block 8 % (callgrind, 96^3, one thread). Its time counts
// as colour time (stats.colorMilliseconds).
void PolygonizeRun::normalsWithColors(const BlockJob& job, Scratch& sc) {
  const auto c0 = std::chrono::steady_clock::now();
  BlockOutput& o = *out[job.bi];
  const size_t nv = o.positions.size();
  for (auto* v : {&sc.x, &sc.y, &sc.z, &sc.gx, &sc.gy, &sc.gz}) v->resize(nv);
  gatherBySubBlock(o, sc, nv);
  o.colors.resize(nv);
  sc.rgba.resize(nv);
  for (size_t q0 = 0, q1 = 0; q0 < nv; q0 = q1) {  // sc.gather holds each sub-block's vertices in turn
    while (q1 < nv && sc.vertexSub[sc.gather[q1]] == sc.vertexSub[sc.gather[q0]]) ++q1;
    sc.color.evaluateActiveWithGradient(*colorProg, *job.prog, sc.x.data() + q0, sc.y.data() + q0, sc.z.data() + q0,
                                        int(q1 - q0), sc.rgba.data() + q0, nullptr, sc.gx.data() + q0,
                                        sc.gy.data() + q0, sc.gz.data() + q0);
  }
  for (size_t q = 0; q < nv; ++q) {
    const uint32_t k = sc.gather[q];
    o.normals[k] = outwardNormal(sc.gx[q], sc.gy[q], sc.gz[q], o.normals[k]);
    o.colors[k] = sc.rgba[q];
  }
  pairs.fetch_add(nv * job.prog->primitiveCount, std::memory_order_relaxed);
  points.fetch_add(nv, std::memory_order_relaxed);
  colorNs.fetch_add(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - c0).count(),
      std::memory_order_relaxed);
}

// The colours of the m vertices sc.gather of o (their points in sc.x, y, z), with active: the
// block's program (field/surface_color.h: the whole walk's colours). The block's, not each
// sub-block's: a walk over the program's ops costs about as much as the points it colours in the
// animorphosis demo (hundreds of maps per program, a dozen vertices per sub-block), so one walk
// per run of 128 vertices instead of one per sub-block halved the colour's time there.
void PolygonizeRun::colorVertices(const ActiveProgram& active, BlockOutput& o, Scratch& sc, size_t m) {
  const auto c0 = std::chrono::steady_clock::now();
  o.colors.resize(o.positions.size());
  sc.rgba.resize(m);
  sc.color.evaluateActive(*colorProg, active, sc.x.data(), sc.y.data(), sc.z.data(), int(m), sc.rgba.data());
  for (size_t q = 0; q < m; ++q) o.colors[sc.gather[q]] = sc.rgba[q];
  colorNs.fetch_add(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - c0).count(),
      std::memory_order_relaxed);
}

// A block output kept within the tolerance while a colour reaching it changed: its vertices
// coloured again with the block's program (sc.active), in their stored order (an output's vertices
// come cell by cell: compact runs).
void PolygonizeRun::recolorKept(BlockOutput& o, Scratch& sc) {
  const size_t nv = o.positions.size();
  sc.x.resize(nv);
  sc.y.resize(nv);
  sc.z.resize(nv);
  sc.gather.resize(nv);
  for (size_t q = 0; q < nv; ++q) {
    sc.x[q] = o.positions[q].x;
    sc.y[q] = o.positions[q].y;
    sc.z[q] = o.positions[q].z;
    sc.gather[q] = uint32_t(q);
  }
  colorVertices(sc.active, o, sc, nv);
}

// Global vertex numbering in block order, then each block's triangle corners resolved: its own
// vertices, or shared edges' vertices owned by a neighbour (kUnresolved where the owner made none).
void PolygonizeRun::stitch(tbb::task_arena& arena, TriangleMesh& mesh) {
  size_t nv = 0, ni = 0;
  for (auto& op : out) {
    if (!op) continue;
    op->vertexOffset = nv;
    op->indexOffset = ni;
    nv += op->positions.size();
    ni += op->corners.size();
  }
  mesh.positions.resize(nv);
  mesh.normals.resize(nv);
  mesh.indices.resize(ni);
  if (colorProg) mesh.colors.resize(nv);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), nBlocks, [&](size_t bi) {
      if (!out[bi]) return;
      const BlockOutput& o = *out[bi];
      std::copy(o.positions.begin(), o.positions.end(), mesh.positions.begin() + std::ptrdiff_t(o.vertexOffset));
      std::copy(o.normals.begin(), o.normals.end(), mesh.normals.begin() + std::ptrdiff_t(o.vertexOffset));
      if (colorProg && o.colors.size() == o.positions.size())
        std::copy(o.colors.begin(), o.colors.end(), mesh.colors.begin() + std::ptrdiff_t(o.vertexOffset));
      for (size_t q = 0; q < o.corners.size(); ++q) {
        uint64_t code = o.corners[q];
        uint32_t index = kUnresolved;
        if (!(code & kExternal)) {
          index = uint32_t(o.vertexOffset + code);
        } else {
          const ExternalVertex& ev = o.externals[size_t(code & ~kExternal)];
          size_t ob = size_t(ev.gi / kBlock) +
                      size_t(g.nb[0]) * (size_t(ev.gj / kBlock) + size_t(g.nb[1]) * size_t(ev.gk / kBlock));
          const BlockOutput* owner = out[ob].get();
          if (owner && !owner->ownedSlot.empty()) {
            int li = ev.gi % kBlock, lj = ev.gj % kBlock, lk = ev.gk % kBlock;
            int32_t slot = owner->ownedSlot[size_t(((lk * kBlock + lj) * kBlock + li) * 3 + ev.axis)];
            if (slot >= 0) index = uint32_t(owner->vertexOffset + size_t(slot));
          }
        }
        mesh.indices[o.indexOffset + q] = index;
      }
    });
  });
}

// Edges whose owner block made no vertex (only if an interval bound was too optimistic): made
// here, once per edge, so the mesh stays watertight. Returns how many.
size_t PolygonizeRun::addOrphanVertices(TriangleMesh& mesh) {
  std::unordered_map<uint64_t, uint32_t> orphans;
  FieldEvaluator evaluator;
  for (size_t bi = 0; bi < nBlocks; ++bi) {
    if (!out[bi]) continue;
    const BlockOutput& o = *out[bi];
    for (size_t q = 0; q < o.corners.size(); ++q) {
      if (mesh.indices[o.indexOffset + q] != kUnresolved) continue;
      const ExternalVertex& ev = o.externals[size_t(o.corners[q] & ~kExternal)];
      uint64_t key =
          ((uint64_t(ev.gk) * uint64_t(g.n[1] + 1) + uint64_t(ev.gj)) * uint64_t(g.n[0] + 1) + uint64_t(ev.gi)) * 3 +
          uint64_t(ev.axis);
      auto it = orphans.find(key);
      if (it == orphans.end()) {
        glm::vec3 grad;
        evaluator.evaluatePoint(program, ev.position, &grad);
        mesh.positions.push_back(ev.position);
        mesh.normals.push_back(outwardNormal(grad.x, grad.y, grad.z, glm::vec3(0, 1, 0)));
        it = orphans.emplace(key, uint32_t(mesh.positions.size() - 1)).first;
      }
      mesh.indices[o.indexOffset + q] = it->second;
    }
  }
  return orphans.size();
}

// The next frame's history: this grid, program, candidate lists and block outputs (moved out).
void PolygonizeRun::saveHistory() {
  if (!s.history || !s.culling) return;
  auto next = std::make_unique<PolygonizeHistory::State>();
  next->origin = g.origin;
  next->h = g.h;
  for (int a = 0; a < 3; ++a) next->n[a] = g.n[a];
  next->subBlockLists = s.subBlockLists;
  next->colors = colorProg != nullptr;
  next->program = program;
  next->superCandidates = std::move(superCandidates);
  next->out = std::move(out);
  next->summary = std::move(summary);
  PolygonizeHistoryAccess::state(*s.history) = std::move(next);
}

double millisecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The colours the blocks did not make (settings.colors): with per-block colours only the orphan
// vertices [stitched, end), else (another colour program) every vertex, in runs between which
// cancel is polled. Sets st.colorMilliseconds (with per-block colours: the blocks' colour time
// summed over their threads, processor time, plus this). False when cancelled.
bool colorAfterMesh(const PolygonizeRun& run, TriangleMesh& mesh, size_t stitched, PolygonizeStats& st) {
  const PolygonizeSettings& s = run.s;
  const auto c0 = std::chrono::steady_clock::now();
  const size_t n = mesh.positions.size();
  mesh.colors.resize(n);
  SurfaceColorEvaluator colors;
  if (run.colorProg) {
    if (n > stitched) colors.evaluate(*run.colorProg, mesh.positions.data() + stitched, n - stitched,
                                      mesh.colors.data() + stitched, s.threads);
    st.colorMilliseconds = double(run.colorNs.load()) * 1e-6 + millisecondsSince(c0);
    return true;
  }
  constexpr size_t kColorRun = 32768;
  const ColorProgram program(s.colorProgram ? *s.colorProgram : run.program);
  for (size_t first = 0; first < n; first += kColorRun) {
    if (s.cancel && s.cancel->load()) return false;
    colors.evaluate(program, mesh.positions.data() + first, std::min(kColorRun, n - first), mesh.colors.data() + first,
                    s.threads);
  }
  st.colorMilliseconds = millisecondsSince(c0);
  return true;
}

// Measuring only (polygonize_stage_times.h): this thread's sink and a lap clock over the stages.
thread_local PolygonizeStageTimes* stageSink = nullptr;

struct StageLaps {
  PolygonizeStageTimes* sink = stageSink;
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
  // Adds the time since the previous lap to *field (nothing without a sink).
  void lap(double PolygonizeStageTimes::*field) {
    if (!sink) return;
    const auto now = std::chrono::steady_clock::now();
    sink->*field += std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
  }
};

}  // namespace

void setPolygonizeStageTimes(PolygonizeStageTimes* sink) { stageSink = sink; }
void setPolygonizePairCulling(bool on) { pairCullingOn = on; }

namespace {
void addStageCounts(PolygonizeStageTimes& t, const PolygonizeStats& st) {
  ++t.calls;
  t.totalMs += st.milliseconds;
  t.blocksTotal += st.blocksTotal;
  t.blocksEvaluated += st.blocksEvaluated;
  t.blocksWithSurface += st.blocksWithSurface;
}
}  // namespace

Result<PolygonizeResult> polygonize(const FieldProgram& program, const PolygonizeSettings& s) {
  auto t0 = std::chrono::steady_clock::now();
  StageLaps laps;
  PolygonizeResult result;
  auto grid = polygonizeGrid(program, s);
  if (!grid) return Error{grid.error()};
  if (grid->empty) {
    result.stats.milliseconds = millisecondsSince(t0);
    return result;  // nothing inside anywhere
  }
  PolygonizeRun run(program, s, *grid);
  PolygonizeStats& st = result.stats;
  st.gridX = run.g.n[0];
  st.gridY = run.g.n[1];
  st.gridZ = run.g.n[2];
  st.cellSize = run.g.h;
  st.blocksTotal = run.nBlocks;
  run.takeHistory();
  program.specialiseAll(run.allPrims);

  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
  tbb::enumerable_thread_specific<Scratch> scratch;
  laps.lap(&PolygonizeStageTimes::setupMs);
  run.cullSuperblocks(arena, scratch);
  laps.lap(&PolygonizeStageTimes::superblocksMs);
  run.listPairCandidates(arena);
  run.cullPairs(arena, scratch);
  laps.lap(&PolygonizeStageTimes::pairsMs);
  const bool finished = run.runBlocks(arena, scratch);
  laps.lap(&PolygonizeStageTimes::blocksMs);
  st.blocksCulled = run.culled.load();
  st.blocksEvaluated = run.evaluated.load();
  st.blocksReused = run.reused.load();
  for (const auto& o : run.out) st.blocksWithSurface += o && !o->corners.empty() ? 1 : 0;
  st.cellsVisited = run.cells.load();
  if (!finished) {
    result.cancelled = true;
    st.pointsEvaluated = run.points.load();
    st.milliseconds = millisecondsSince(t0);
    return result;
  }
  run.stitch(arena, result.mesh);
  laps.lap(&PolygonizeStageTimes::stitchMs);
  const size_t stitched = result.mesh.positions.size();
  st.orphanVertices = run.addOrphanVertices(result.mesh);
  laps.lap(&PolygonizeStageTimes::orphansMs);
  run.saveHistory();
  laps.lap(&PolygonizeStageTimes::historyMs);
  st.pointsEvaluated = run.points.load() + st.orphanVertices;
  st.primitiveEvaluations = run.pairs.load();
  if (s.colors && !colorAfterMesh(run, result.mesh, stitched, st)) {
    result.mesh = TriangleMesh{};  // as a cancelled sweep: empty
    result.cancelled = true;
    st.milliseconds = millisecondsSince(t0);
    return result;
  }
  laps.lap(&PolygonizeStageTimes::colorsMs);
  if (s.progress) s.progress(1.0f);
  st.milliseconds = millisecondsSince(t0);
  if (laps.sink) {
    addStageCounts(*laps.sink, st);
    laps.sink->blocksVisited += s.culling ? run.nBlocks - run.blocksOutsideFineLevel() : run.nBlocks;
  }
  return result;
}

}  // namespace animorph
