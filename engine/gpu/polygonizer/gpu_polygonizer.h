#pragma once
// GPU polygoniser (docs/design.md §6, docs/gpu-polygonizer.md): marching cubes of a
// FieldProgram, or of the morph of two, in Vulkan compute, agreeing with the
// CPU polygoniser (poly/polygonizer.h) on the same grid. Per frame: the
// programs are uploaded as small buffers inside the command buffer; a coarse
// pass lists per 8^3-cell block the primitives that reach it and culls blocks
// whose field interval has one sign; the active blocks are compacted by a
// prefix sum; the field is evaluated only there; vertices (one per crossing
// edge, shared by the cells around it) and triangles are placed by prefix sums;
// normals come from the field gradient. The outputs are vertex/index buffers
// and a VkDrawIndexedIndirectCommand, so the editor draws with no CPU read-back.
// When a frame outgrows the buffers the draw is empty, the counters say so, and
// the next record() (or polygonize(), at once) grows them and redoes the frame:
// nothing is ever truncated silently.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "core/field/field_program.h"
#include "core/math/bounds.h"
#include "core/standin_morph/morph_field.h"
#include "core/poly/mesh.h"
#include "core/poly/polygonizer.h"
#include "gpu/render/scene_renderer.h"
#include "core/util/result.h"

namespace animorph::gpu {

// The morph method is the core's (standin_morph/morph_field.h): Interpolation,
// m = (1 - w) f1 + w f2, and SpaceTime (docs/design.md §5 and
// include_shared/morph_field.h) combine two programs here;
// SkeletonCorrespondence is not a combination of two fixed programs (its
// stand-ins move with w): it reaches the GPU flattened into one program
// (morphImplicitField, GpuField::single), and unsupported() says so for a pair.
using animorph::MorphMethod;

// What to polygonise: one program, or the morph of two ("evaluate two programs
// and combine"; the formulas are in include_shared/morph_field.h, shared with C++).
struct GpuField {
  const FieldProgram* a = nullptr;  // required
  const FieldProgram* b = nullptr;  // set: the morph of a and b
  MorphMethod method = MorphMethod::Interpolation;
  float weight = 0.5f;     // interpolation: w (0: a, 1: b)
  float morphTime = 0.5f;  // space-time: t (0: a, 1: b)
  float timeScale = 1.0f;  // space-time: scale of t against field values
  float a0 = 1.0f, a1 = 1.0f, a2 = 1.0f, a3 = 1.0f;  // space-time: bounded-blending parameters
  // The program whose colours the vertices take (PolygonizeSettings::colorProgram: the same surface,
  // finer colours, e.g. a morph's stand-ins split into their colour samples); null: a's own. Used by
  // the colour pass only (GpuPolygonizeSettings::colors), walked whole at every vertex.
  const FieldProgram* colors = nullptr;

  static GpuField single(const FieldProgram& p) { return {&p}; }
  static GpuField interpolation(const FieldProgram& a, const FieldProgram& b, float w) {
    GpuField f{&a, &b};
    f.weight = w;
    return f;
  }
  static GpuField spaceTime(const FieldProgram& a, const FieldProgram& b, float t, float timeScale = 1.0f,
                            float a0 = 1.0f, float a1 = 1.0f, float a2 = 1.0f, float a3 = 1.0f) {
    GpuField f{&a, &b, MorphMethod::SpaceTime};
    f.morphTime = t;
    f.timeScale = timeScale;
    f.a0 = a0;
    f.a1 = a1;
    f.a2 = a2;
    f.a3 = a3;
    return f;
  }
};

struct GpuPolygonizeSettings {
  // Cells along the longest side of the grid bounds (cubic cells), 2..512.
  // The cost follows the surface with culling, the volume without.
  int resolution = 128;
  // Grid bounds; default as the CPU polygoniser: the programs' interval-tightened
  // bounds (the union for a morph; space-time blending adds 10%) grown by marginCells.
  std::optional<Bounds> bounds;
  float marginCells = 2.0f;
  // The grid as it is (origin, cubic cell size, 1..512 cells a side), overriding resolution, bounds
  // and marginCells: a scrubbed preview holds the previous frame's grid while the shape fits in it
  // (poly/scrubbing_grid.h), so temporal coherence applies to moving shapes too.
  std::optional<PolygonizeGrid> grid;
  // Per-block primitive lists and interval culling. Off: every block is
  // evaluated with every primitive (same mesh, slower).
  bool culling = true;
  // Where the shaders read the programs: Auto picks a uniform buffer on GPUs when
  // the programs fit in 64 KiB, a storage buffer on CPU devices (lavapipe) or
  // beyond. Same results either way; tests force each.
  enum class PoolBuffer : uint8_t { Auto, Uniform, Storage };
  PoolBuffer poolBuffer = PoolBuffer::Auto;
  // Specialise the field shaders on what the programs use (op codes, primitive
  // classes, skeleton and map kinds, combine mode): one pipeline variant per set,
  // created on first use and kept. Off: the generic variant (same mesh; tests
  // compare both). On lavapipe the generic interpreter runs every op's code at
  // every op (no real branches), so specialising halves the fine passes.
  bool specialise = true;
  // Scans of at most AM_POLY_SCAN_SINGLE_MAX elements (grids up to 256^3) run in one
  // workgroup, compaction and indirect arguments included: one dispatch instead of five
  // after the coarse pass and four after the cells pass (on lavapipe each costs ~0.1 ms).
  // Off: the multi-group scan that longer arrays use (same mesh; tests compare both).
  bool singleWorkgroupScan = true;
  // Solid-noise displacement of the vertices along their normals by amplitude (m) *
  // solidNoise(frequency (1/m) * p), after polygonising: the CPU's displaceBySolidNoise
  // (docs/design.md §5, the morph's noise track). 0: none (no pass).
  float noiseAmplitude = 0.0f;
  float noiseFrequency = 1.0f;
  // Workgroups a row of the fine passes' dispatch (0: AM_POLY_MAX_DISPATCH_X, the least every
  // device allows); the blocks past a row go on in the next. Tests narrow it to run that path.
  uint32_t dispatchRow = 0;
  // Per-region programs (docs/gpu-polygonizer.md, "Per-region programs"): each superblock's passes
  // walk the programs specialised on the CPU to the primitives reaching it (gpu_region_op_lists.h)
  // instead of the whole programs. Auto: for programs of more than kRegionListMinOps ops, and for
  // any whose whole walk would outrun the device's loop limit (lavapipe). Same mesh either way
  // (tests compare On and Off); On costs a CPU specialisation per superblock each frame.
  enum class RegionPrograms : uint8_t { Auto, Off, On };
  RegionPrograms regionPrograms = RegionPrograms::Auto;
  static constexpr size_t kRegionListMinOps = 256;
  // Refuse programs whose loops could run past the device's per-invocation loop limit (lavapipe:
  // GpuPolygonizer::loopLimit). Tests turn it off to run the shaders' own detection of cut loops,
  // which fails the polygonisation instead of drawing a wrong mesh.
  bool loopBudgetCheck = true;
  // With region lists: run the normals pass once per vertex of its invocations' four (four
  // dispatches, each invocation walking one region's list once). Automatic where one dispatch could
  // outrun the device's loop limit (two regions among four vertices); tests force it.
  bool normalsPerVertex = false;
  // Vertex colours (docs/gpu-polygonizer.md, "Colour"): for a single program whose primitives carry
  // colours, a pass after the normals gives each vertex the CPU's surface colour
  // (field/surface_color.h), RGBA8 in the w of its normal (AM_POLY_COLOR_TAG); readBack() returns
  // them. Off, or a morph of two programs, or a program too long for the device's loop limit: none
  // (w stays 0, the draw's one tone; GpuPolygonizeStats::colors says which).
  bool colors = true;
  // The colour pass walks the vertex's region's list rather than the whole program, so its cost
  // follows the local op count and programs too long for a whole walk on lavapipe get colours:
  // program A's lists where the frame walks per-region programs (regionPrograms), a colour program's
  // own lists (GpuField::colors, regions of 2 blocks a side) always. Off: the whole walk (the same
  // colours; tests compare both).
  bool colorRegionLists = true;
  // Temporal coherence (docs/gpu-polygonizer.md, "Temporal coherence"): a frame prepared with the
  // previous recorded frame's (prepare(..., previous)) on the same grid, programs of the same
  // structure, reuses a block's kept corner values instead of evaluating them when the field
  // provably moved there (primitiveChangeBounds summed over the primitives reaching its superblock,
  // accumulated since the values were made) by so little that no corner changes sign and no vertex
  // moves by more than this many cells (the CPU's rule, poly/polygonizer.h). 0: only blocks nothing
  // reaching changed (the mesh is exactly a full sweep's); below 0: off (nothing kept). Normals are
  // evaluated afresh at the vertices. Keeping costs 2.9 KiB of device memory per block of the grid;
  // grids past 256 MiB of it keep nothing.
  float reuseToleranceCells = 0.1f;
  // Initial buffer capacities (0: automatic). They grow when a frame overflows.
  uint32_t initialBlockCapacity = 0;
  uint32_t initialVertexCapacity = 0;
  uint32_t initialTriangleCapacity = 0;
};

struct GpuPolygonizeStats {
  int gridX = 0, gridY = 0, gridZ = 0;  // cells per axis
  float cellSize = 0.0f;
  uint32_t blocksTotal = 0;   // 8^3-cell blocks of the grid
  uint32_t blocksActive = 0;  // blocks the fine passes evaluated
  uint32_t vertices = 0, triangles = 0;
  uint32_t regrows = 0;       // polygonize(): frames redone after growing the buffers
  bool overflowed = false;    // record(): the frame kFramesInFlight ago did not fit (it is redone now)
  bool uniformPool = true;    // programs read from a uniform buffer (else storage)
  uint32_t features = 0, kinds = 0;  // the pipeline variant (AM_FEAT_* / AM_KIND_*; all bits: generic)
  // Per-region programs (GpuPolygonizeSettings::regionPrograms): used, the longest list's ops and
  // all lists' ops together, and the CPU time spent building them (ms, part of the record).
  bool regionLists = false;
  uint32_t regionLongestOps = 0;
  uint32_t regionBlocks = 0;  // blocks a side of the regions the blocks' lists are for (4: superblocks)
  uint32_t normalsDispatches = 1;  // 4: the normals pass ran once per vertex of its invocations
  bool colors = false;  // the vertices carry colours (GpuPolygonizeSettings::colors)
  bool colorRegionLists = false;  // the colour pass walked per-region lists (GpuPolygonizeSettings::colorRegionLists)
  // The record created the colour pass's pipeline itself (on its thread: a stall on lavapipe); false
  // when it was made before (an earlier frame, or prewarm()).
  bool colorPipelineMadeInRecord = false;
  uint64_t regionOpsTotal = 0;
  double regionListMs = 0.0;
  // The frame's host preparation (grid bounds, programs packed, region lists: GpuPreparedFrame):
  // true when this record or polygonize() computed it itself, false when it used a prepared frame
  // given to it; prepareMs: the host time it spent on that here (0 with a prepared frame).
  bool preparedInRecord = true;
  double prepareMs = 0.0;
  // Temporal coherence (GpuPolygonizeSettings::reuseToleranceCells): the frame had the change bounds
  // from the previous frame (a prepared frame of its successor on the same grid), and the blocks
  // whose corners were the kept ones (read back with the other counters).
  bool coherent = false;
  uint32_t blocksReused = 0;
  double milliseconds = 0.0;  // polygonize(): wall time from submit to completion (all passes)
  // polygonize(): GPU time per pass from timestamps (0 when the queue has none):
  // uploads, coarse (lists + intervals), block compaction, corners + cells, vertex/triangle scan, emit.
  double passMs[6] = {0, 0, 0, 0, 0, 0};
};

class GpuPolygonizer;

// A frame's host preparation, made once and on any thread (GpuPolygonizer::prepare): the grid (the
// programs' interval-tightened bounds: 16-29 ms for the animorphosis demo's C(t)), the programs
// packed into the pool (3-8 ms) and the per-region op lists. A record() given one only uploads and
// records. It refers to the field's programs, which must outlive it unchanged.
class GpuPreparedFrame {
 public:
  ~GpuPreparedFrame();
  GpuPreparedFrame(const GpuPreparedFrame&) = delete;
  GpuPreparedFrame& operator=(const GpuPreparedFrame&) = delete;
  // Host time the preparation took (ms).
  double milliseconds() const;
  // Whether it carries change bounds from a previous frame (temporal coherence).
  bool hasChangeBounds() const;

 private:
  friend class GpuPolygonizer;
  struct Data;
  explicit GpuPreparedFrame(std::unique_ptr<Data> d);
  std::unique_ptr<Data> d_;
};

class GpuPolygonizer {
 public:
  // Pipelines, the marching-cubes table and small initial buffers. Errors: a device short of
  // what the passes need (deviceShortfall), missing shaders, Vulkan failures (out of memory included).
  static Result<std::unique_ptr<GpuPolygonizer>> create(Context& ctx);
  // What a device with these limits lacks for the polygoniser's workgroups (shared memory,
  // invocations), empty when it has enough.
  static std::string deviceShortfall(const VkPhysicalDeviceLimits& limits);
  ~GpuPolygonizer();
  GpuPolygonizer(const GpuPolygonizer&) = delete;
  GpuPolygonizer& operator=(const GpuPolygonizer&) = delete;

  // Why the GPU cannot polygonise field (empty when it can). Callers use the CPU path otherwise.
  // A program's size is no reason: on a device that stops long shader loops (loopLimit, lavapipe)
  // programs whose whole walk would outrun it are walked per region (regionPrograms). What remains
  // (a region reached by more primitives than the limit allows) fails in polygonize() and record()
  // with the figures, and a frame whose loops still run out is flagged and never drawn.
  static std::string unsupported(const GpuField& field);
  // The grid field is polygonised on under s (the CPU polygoniser's rule, or s.grid), empty when the
  // field is inside nowhere; on any thread, no device (for a field without bounds it computes the
  // programs' interval-tightened bounds). Errors: a resolution out of 2..512, bad bounds or grid, an
  // unbounded field without bounds.
  static Result<PolygonizeGrid> grid(const GpuField& field, const GpuPolygonizeSettings& s);
  // Loop iterations after which the device stops every loop of a shader invocation, all loops
  // together (0: no such limit). llvmpipe (lavapipe): AM_POLY_LLVMPIPE_LOOP_LIMIT.
  static uint64_t loopLimit(const VkPhysicalDeviceProperties& properties);

  // Records one polygonisation into cmd (outside any render pass), no CPU
  // read-back: the editor's per-frame call, then draw generatedMesh(). frameSerial
  // numbers the frame (as SceneRenderer::record); the counters of frame
  // frameSerial - kFramesInFlight, which the caller guarantees has completed,
  // are read here, and if that frame overflowed the buffers grow first (waiting
  // for the device). Buffers may be replaced: take generatedMesh() after record().
  // A record whose loops the device cut short (lavapipe's loop limiter) draws nothing; when it
  // walked per-region lists not yet in their sparest form, it counts as overflowed (lastStats,
  // recordFitted false: record the shape again) and the next records walk single-block lists (and
  // the normals one vertex a dispatch), as polygonize() redoes its frame (cutFramesRedone).
  // Errors: unsupported field, bad settings or bounds, an earlier record whose loops the device
  // cut short in the sparest form (that frame drew nothing: use the CPU), Vulkan failures.
  Status record(VkCommandBuffer cmd, uint64_t frameSerial, const GpuField& field, const GpuPolygonizeSettings& s);
  // The same with the frame's host preparation done beforehand (prepare()): nothing is computed
  // here but the upload and the commands. A prepared frame of other programs or settings, for
  // another loop limit, or made before a cut frame made the region lists conservative, is not used:
  // the record prepares on the spot as above (lastStats().preparedInRecord, preparesInRecord()).
  Status record(VkCommandBuffer cmd, uint64_t frameSerial, const GpuField& field, const GpuPolygonizeSettings& s,
                const GpuPreparedFrame* prepared);

  // The host preparation of a frame of field under s for a device whose loop limit is loopLimit
  // (GpuPolygonizer::loopLimit; 0: none), on any thread (no device needed). Errors: as record()'s
  // for bad settings or bounds, unsupported fields, programs that cannot be packed, region lists
  // that outrun the loop limit.
  // With previous (the frame recorded just before this one will be, prepared the same way; its
  // programs alive during the call): also the change bounds per block for temporal coherence, when
  // the grid, the programs' structure and the morph's parameters are the same (else none: that
  // frame evaluates every block).
  static Result<std::shared_ptr<const GpuPreparedFrame>> prepare(const GpuField& field, const GpuPolygonizeSettings& s,
                                                                 uint64_t loopLimit,
                                                                 const GpuPreparedFrame* previous = nullptr,
                                                                 bool conservativeRegions = false);
  // Whether this polygoniser builds its region lists conservatively now (after a frame whose loops
  // the device cut): frames prepared for it must be prepared so (prepare's last argument), or its
  // records prepare again on the spot.
  bool conservativeRegions() const;
  // Records and polygonize() calls that prepared their frame themselves (no usable prepared frame).
  uint64_t preparesInRecord() const;
  // Records whose loops the device cut and that a later record redid sparing it more (see record()).
  uint64_t cutFramesRedone() const;

  // Starts compiling, on a background thread, the shader pipelines record() and polygonize() will
  // need for fields like this one (same operators, primitive kinds and morph method), so that the
  // first of them does not stall its frame: on lavapipe a field's four pipelines take about a
  // second to compile, on the thread that creates them. A record() that needs them meanwhile
  // waits for the compilation. No-op when they exist or are under way, or for an unsupported
  // field; compilation errors surface in record(). A field with colours (colors on) has its colour
  // pass's pipeline compiled too.
  void prewarm(const GpuField& field, const GpuPolygonizeSettings& s = {});
  // True when record() of field would not wait for pipelines to compile (they exist, or a
  // prewarm has finished them; the colour pass's too where the field has colours). Interactive callers prewarm and draw what they have meanwhile.
  bool ready(const GpuField& field, const GpuPolygonizeSettings& s = {}) const;
  // Waits up to timeoutSec for the pipelines being compiled in the background. Returns all done.
  bool waitForCompilation(double timeoutSec) const;
  // Pipeline variants made or being made (one per kind of field: operators, primitives, morph method).
  size_t variantCount() const;

  // Device buffers of the last recorded mesh for SceneRenderer (Scene::generatedMeshes).
  GeneratedMeshDraw generatedMesh(const glm::vec4& color = {0.62f, 0.62f, 0.62f, 1.0f}) const;

  // Synchronous polygonisation (CLI, tests, benchmarks): records, submits and
  // waits; on overflow grows the buffers and redoes it until the mesh fits.
  // Errors: as record(), device lost, a mesh beyond the device's buffer limits.
  Result<GpuPolygonizeStats> polygonize(const GpuField& field, const GpuPolygonizeSettings& s);
  // The same with a prepared frame (see record()'s overload).
  Result<GpuPolygonizeStats> polygonize(const GpuField& field, const GpuPolygonizeSettings& s,
                                        const GpuPreparedFrame* prepared);

  // The mesh of the last polygonize() (positions, normals, indices; colours, linear, when
  // lastStats().colors) copied to host memory. Errors: nothing polygonised yet, Vulkan failures.
  Result<TriangleMesh> readBack();

  // Stats of the last polygonize(), or of the last record() whose counters were read.
  const GpuPolygonizeStats& lastStats() const { return stats_; }
  // Once the record of frameSerial has completed (the caller's fence): whether its mesh fitted the
  // buffers. Its counters become lastStats(); if it overflowed the buffers grow now, for the record
  // that redoes it (which then need not wait kFramesInFlight records to find out). Errors: the
  // record's counters were taken already or overwritten; growing failed.
  Result<bool> recordFitted(uint64_t frameSerial);

 private:
  Status absorbCounters(uint32_t slot);  // the counters of the record in a read-back slot, once
  struct Impl;
  explicit GpuPolygonizer(Context& ctx);
  std::unique_ptr<Impl> impl_;
  GpuPolygonizeStats stats_;
};

}  // namespace animorph::gpu
