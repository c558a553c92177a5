#include "gpu/polygonizer/gpu_polygonizer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <future>
#include <limits>
#include <tuple>

#include "gpu/polygonizer/field_pipeline_cache.h"
#include "gpu/polygonizer/gpu_color_table.h"
#include "gpu/polygonizer/gpu_field_program.h"
#include "gpu/polygonizer/gpu_region_op_lists.h"
#include "core/poly/program_change.h"
#include "core/poly/solid_noise.h"
#include "core/poly/marching_cubes_table.h"
#include "poly_constants.h"
#include "gpu/vulkan/command_resources.h"
#include "gpu/vulkan/shader_module.h"
#include "shared_constants.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

namespace {

// std140 mirror of PolyParams in shaders/include/poly_common.glsl.
struct PolyParams {
  glm::vec4 gridOrigin;
  glm::uvec4 gridCells;
  glm::uvec4 gridBlocks;
  glm::uvec4 progA;
  glm::uvec4 progB;
  glm::vec4 thresholds;
  glm::uvec4 modes;
  glm::vec4 morph0;
  glm::vec4 morph1;
  glm::uvec4 caps;
  glm::vec4 extra;
  glm::uvec4 superBlocks;
  glm::uvec4 regions;
  glm::uvec4 regionLists;
  glm::uvec4 colorPass;
};
static_assert(sizeof(PolyParams) == 15 * 16);

constexpr uint32_t kTableVec4 = 256 + 64;  // poly_table.glsl: the marching-cubes cases, then the noise permutation
constexpr VkDeviceSize kVertexStride = GeneratedMeshDraw::kVertexStride;  // poly_emit_main.glsl: vec4 positions, normals
constexpr uint32_t kTimestamps = 7;

struct Grid {
  glm::vec3 origin{0.0f};
  float h = 1.0f;
  uint32_t n[3] = {1, 1, 1};
  uint32_t nb[3] = {1, 1, 1};
  uint32_t blocks() const { return nb[0] * nb[1] * nb[2]; }
  uint32_t superAxis(int a) const { return (nb[a] + AM_POLY_SUPER - 1) / AM_POLY_SUPER; }
  uint32_t superBlocks() const { return superAxis(0) * superAxis(1) * superAxis(2); }
};

// The CPU polygoniser's grid rule (poly/polygonizer.cpp), so both meet on the same grid; s.grid
// as it is. empty (may be null): set when the field is inside nowhere (the grid is then 1 cell).
Result<Grid> makeGrid(const GpuField& field, const GpuPolygonizeSettings& s, bool* empty = nullptr) {
  Grid g;
  int res = s.resolution;
  if (empty) *empty = false;
  if (s.grid) {
    const PolygonizeGrid& o = *s.grid;
    bool ok = o.cellSize > 0.0f && std::isfinite(o.cellSize) && std::isfinite(o.origin.x) && std::isfinite(o.origin.y) &&
              std::isfinite(o.origin.z);
    for (int a = 0; a < 3; ++a) ok = ok && o.cells[a] >= 1 && o.cells[a] <= 512;
    if (!ok)
      return Error{"GPU polygoniser: the grid override has no cells, more than 512 a side, a cell size <= 0 or a "
                   "non-finite origin"};
    g.origin = o.origin;
    g.h = o.cellSize;
    for (int a = 0; a < 3; ++a) g.n[a] = uint32_t(o.cells[a]);
  } else if (s.bounds) {
    Bounds box = *s.bounds;
    if (box.empty() || !std::isfinite(box.diagonal()) || box.diagonal() <= 0.0f)
      return Error{"GPU polygoniser: the bounds override is empty or not finite"};
    float L = std::max({box.size().x, box.size().y, box.size().z});
    g.h = L / float(res);
    for (int a = 0; a < 3; ++a) g.n[a] = uint32_t(std::max(1, int(std::lround(box.size()[a] / g.h))));
    g.origin = box.center() - 0.5f * g.h * glm::vec3(float(g.n[0]), float(g.n[1]), float(g.n[2]));
  } else {
    Bounds box;
    for (const FieldProgram* p : {field.a, field.b}) {
      if (!p) continue;
      if (p->unbounded())
        return Error{"GPU polygoniser: the field is inside everywhere far from its primitives (unbounded); give bounds"};
      Bounds t = p->tightBounds();
      if (!t.empty()) box.add(t);
    }
    if (box.empty()) {  // n stays 1: an empty grid, nothing inside anywhere
      if (empty) *empty = true;
      return g;
    }
    if (field.b && field.method == MorphMethod::SpaceTime) {
      glm::vec3 pad = 0.05f * box.size();
      box.min -= pad;
      box.max += pad;
    }
    float L = std::max({box.size().x, box.size().y, box.size().z, 1e-6f});
    float margin = std::max(0.0f, s.marginCells);
    float usable = float(res) - 2.0f * margin;
    g.h = usable >= 1.0f ? L / usable : L / float(res);
    for (int a = 0; a < 3; ++a)
      g.n[a] = uint32_t(std::clamp(int(std::ceil(box.size()[a] / g.h + 2.0f * margin)), 1, res));
    g.origin = box.center() - 0.5f * g.h * glm::vec3(float(g.n[0]), float(g.n[1]), float(g.n[2]));
  }
  for (int a = 0; a < 3; ++a) g.nb[a] = (g.n[a] + AM_POLY_BLOCK - 1) / AM_POLY_BLOCK;
  return g;
}

VkDeviceSize roundCapacity(VkDeviceSize need) { return std::max<VkDeviceSize>(256, std::bit_ceil(need)); }

void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst, VkAccessFlags srcAccess,
             VkAccessFlags dstAccess) {
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  mb.srcAccessMask = srcAccess;
  mb.dstAccessMask = dstAccess;
  vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &mb, 0, nullptr, 0, nullptr);
}

void computeToCompute(VkCommandBuffer cmd) {
  barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
          VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

// Why field's loops would outrun limit by the estimate (empty when not, or limit is 0).
std::string loopBudgetReason(const GpuField& field, uint64_t limit) {
  if (limit == 0 || !field.a) return {};
  const uint64_t need = gpuLoopIterationEstimate(*field.a, field.b);
  if (need + 64 < limit) return {};
  // Short: the editor's status bar shows it.
  return "the programs (" + std::to_string(field.a->primitiveCount() + (field.b ? field.b->primitiveCount() : 0)) +
         " primitives, " + std::to_string(field.a->ops.size() + (field.b ? field.b->ops.size() : 0)) + " ops) need ~" +
         std::to_string(need) + " shader loop iterations per invocation; llvmpipe stops a shader's loops after " +
         std::to_string(limit);
}

// Whether the passes walk per-region op lists for field under s (GpuPolygonizeSettings::regionPrograms).
bool useRegionLists(const GpuField& field, const GpuPolygonizeSettings& s, uint64_t limit) {
  using R = GpuPolygonizeSettings::RegionPrograms;
  if (s.regionPrograms != R::Auto || !field.a) return s.regionPrograms == R::On;
  const size_t ops = field.a->ops.size() + (field.b ? field.b->ops.size() : 0);
  if (ops > GpuPolygonizeSettings::kRegionListMinOps) return true;
  return limit != 0 && gpuLoopIterationEstimate(*field.a, field.b) + 64 >= limit;
}

// The world box of each region of grid g, a cube of 2^shift blocks a side (shift 2: the
// superblocks), in the shaders' order, grown by what the passes read beyond it (the normal step's
// reach, PolyParams::extra.x) and a hundredth of a cell more, so that the CPU's test of a
// primitive's bound against it admits every primitive the shaders' test admits for its blocks.
// parentOf: each region's superblock.
std::vector<Bounds> regionBoxes(const Grid& g, uint32_t shift, float grow, glm::uvec3& dims,
                                std::vector<uint32_t>& parentOf) {
  std::vector<Bounds> boxes;
  const uint32_t side = 1u << shift, span = side * AM_POLY_BLOCK;
  for (int a = 0; a < 3; ++a) dims[a] = (g.nb[a] + side - 1) / side;
  boxes.reserve(size_t(dims.x) * dims.y * dims.z);
  parentOf.clear();
  const float pad = grow + 0.01f * g.h;
  const uint32_t toSuper = 2 - shift;
  for (uint32_t z = 0; z < dims.z; ++z)
    for (uint32_t y = 0; y < dims.y; ++y)
      for (uint32_t x = 0; x < dims.x; ++x) {
        const glm::uvec3 c0(x * span, y * span, z * span);
        const glm::uvec3 c1 = glm::min(c0 + glm::uvec3(span), glm::uvec3(g.n[0], g.n[1], g.n[2]));
        Bounds b;
        b.add(g.origin + g.h * glm::vec3(c0) - glm::vec3(pad));
        b.add(g.origin + g.h * glm::vec3(c1) + glm::vec3(pad));
        boxes.push_back(b);
        parentOf.push_back((x >> toSuper) + g.superAxis(0) * ((y >> toSuper) + g.superAxis(1) * (z >> toSuper)));
      }
  return boxes;
}

// A frame's per-region lists: the superblocks' (with their primitive masks: the coarse pass's
// candidates and its superblock intervals) and those the blocks walk -- the same, or where a
// superblock's walk would outrun the device's loop limit, lists of cubes of 2 blocks or of single
// blocks (their candidates: their superblock's primitives).
struct FrameRegions {
  RegionOpLists super, blocks;
  uint32_t shift = 2;  // the blocks' regions: 2^shift blocks a side
  glm::uvec3 dims{1u};  // the blocks' regions per axis
};

Result<FrameRegions> buildRegionLists(const GpuField& field, const Grid& g, uint64_t limit, bool check,
                                      bool conservative, PackedFieldPrograms& pk) {
  FrameRegions fr;
  const float grow = 2.0f * 0.05f * g.h;  // PolyParams::extra.x: twice the normal step
  std::vector<uint32_t> parentOf;
  const std::vector<Bounds> supers = regionBoxes(g, 2, grow, fr.dims, parentOf);
  fr.super = appendRegionOpLists(*field.a, field.b, supers, pk, true);
  fr.blocks = fr.super;
  auto fits = [&](uint64_t loops) { return limit == 0 || !check || loops + 64 < limit; };
  const size_t poolBefore = pk.pool.size();
  for (int shift = 1;
       shift >= 0 && (conservative || !fits(std::max(fr.blocks.longestCoarse, fr.blocks.longestFine))); --shift) {
    pk.pool.resize(poolBefore);  // drop a coarser attempt
    glm::uvec3 dims;
    const std::vector<Bounds> boxes = regionBoxes(g, uint32_t(shift), grow, dims, parentOf);
    fr.blocks = appendRegionOpLists(*field.a, field.b, boxes, pk, false, &fr.super, &parentOf);
    fr.shift = uint32_t(shift);
    fr.dims = dims;
  }
  // A superblock whose own interval walk would outrun the limit is not tested as a whole (its
  // table entry says so: AM_POLY_NONE); its blocks test themselves with their shorter lists.
  uint64_t superWalk = 0;
  for (uint32_t r = 0; fr.shift < 2 && r < fr.super.regions; ++r) {
    if (fits(fr.super.intervalWalk[r]) && !conservative) superWalk = std::max(superWalk, fr.super.intervalWalk[r]);
    else pk.pool[fr.super.table + r] = glm::uvec4(AM_POLY_NONE, 0u, AM_POLY_NONE, 0u);
  }
  const uint64_t need = std::max({superWalk, fr.blocks.longestCoarse, fr.blocks.longestFine});
  if (!fits(need))
    return Error{"a block of the grid needs ~" + std::to_string(need) + " shader loop iterations per invocation (its op list " +
                 std::to_string(fr.blocks.longestOps) + " ops); llvmpipe stops a shader's loops after " +
                 std::to_string(limit) + " (a finer grid has smaller blocks)"};
  return fr;
}

// A frame's host half (GpuPreparedFrame): the grid, the programs packed, the region lists.
struct FramePrep {
  Grid g;
  PackedFieldPrograms pk;
  FrameRegions fr;
  bool lists = false;         // the passes walk per-region lists (useRegionLists)
  bool conservative = false;  // the lists were built conservatively (Impl::conservativeRegions)
  double regionListMs = 0.0;
  uint32_t colorTable = 0;    // the colour pass's table in pk.pool (0: no colour stream)
  ColorProgramWalk colorWalk; // a colour program of its own (field.colors), else program A's walk
  uint32_t colorMaps = 0;     // the table's maps part (colorTableMaps; the clay tone before it)
  bool colorLists = false;    // the colour pass walks per-region lists (A's, or colorWalk.lists)
  uint32_t colorListShift = 0;  // their regions: cubes of 2^shift blocks
};

// The program whose colours the colour pass gives field's vertices under s (null: no colour stream).
const FieldProgram* colorSourceOf(const GpuField& field, const GpuPolygonizeSettings& s) {
  const FieldProgram* source = field.colors ? field.colors : field.b ? nullptr : field.a;
  return s.colors && source && programHasColors(*source) ? source : nullptr;
}

// A colour program's region boxes: cubes of 2^shift blocks of grid g, and the superblocks that
// narrow their candidates (as buildRegionLists makes them).
struct ColorRegionBoxes {
  std::vector<Bounds> regions, supers;
  std::vector<uint32_t> parentOf;
  ColorRegions where() const { return {&regions, supers.empty() ? nullptr : &supers, &parentOf}; }
};
ColorRegionBoxes colorRegionBoxes(const Grid& g, uint32_t shift) {
  ColorRegionBoxes b;
  const float grow = 2.0f * 0.05f * g.h;  // buildRegionLists' (PolyParams::extra.x: twice the normal step)
  glm::uvec3 dims;
  std::vector<uint32_t> unused;
  b.regions = regionBoxes(g, shift, grow, dims, b.parentOf);
  if (shift < 2) b.supers = regionBoxes(g, 2, grow, dims, unused);
  return b;
}

// The regions of a colour program's own lists: pairs of blocks a side. It is walked without the
// block masks (they are the field program's), so its lists are finer than the superblocks; and
// they do not need the field's lists (a morph's field program is often short, its colour program long).
constexpr uint32_t kColorProgramListShift = 1;

// Vertex colours (docs/gpu-polygonizer.md, "Colour"): a single program with colours, or a colour
// program of its own, packed after p's programs and lists with its colour table. With
// s.colorRegionLists the pass walks a list per region: program A's where p has region lists, a
// colour program's own (built here, kColorProgramListShift); else the whole program. That walk must
// fit the loop limit with room (the estimates leave out the kernels' inner loops), else no colour stream.
Status prepareColors(const GpuField& field, const GpuPolygonizeSettings& s, uint64_t limit, FramePrep& p) {
  if (!colorSourceOf(field, s)) return {};
  const bool lists = s.colorRegionLists && (field.colors || p.lists);
  // The whole walk: twice the estimate (it leaves out the kernels' inner loops). A list's walk: five
  // times, measured on lavapipe (the demo's dinosaur, single-block lists: ~17 700 estimated was cut at
  // 65 535, ~12 500 at 96^3 ran): a SIMD group's lanes may lie in several blocks, each one more walk.
  auto fits = [&](uint64_t walk) { return limit == 0 || (lists ? 5 : 2) * walk + 64 < limit; };
  if (field.colors) {
    if (!lists && !fits(colorWalkLoopEstimate(*field.colors))) return {};
    const size_t poolBefore = p.pk.pool.size();
    ColorRegionBoxes boxes;
    if (lists) boxes = colorRegionBoxes(p.g, kColorProgramListShift);
    p.colorListShift = kColorProgramListShift;
    Result<ColorProgramWalk> w = appendColorProgram(*field.colors, p.pk, lists ? boxes.where() : ColorRegions{});
    if (!w) return Error{"GPU polygoniser: " + w.error()};
    if (lists && !fits(w->longestListWalk)) {
      p.pk.pool.resize(poolBefore);
      return {};
    }
    p.colorWalk = *w;
    p.colorTable = p.colorWalk.table;
    p.colorMaps = p.colorWalk.maps;
  } else {
    if (!fits(lists ? p.fr.blocks.longestColorWalk : colorWalkLoopEstimate(*field.a))) return {};
    p.colorTable = appendColorTable(*field.a, p.pk);
    p.colorMaps = colorTableMaps(*field.a, p.colorTable);
    p.colorListShift = p.fr.shift;
  }
  p.colorLists = lists;
  return {};
}

// What prepareColors adds to the pool for field under s without region lists (those make the pool
// a storage buffer anyway): a colour program's records and its colour table, or program A's table.
// prewarm() and ready() add it to the programs' shape, so that near the uniform pool's size they
// pick the variant the frame will.
size_t colorPoolWords(const GpuField& field, const GpuPolygonizeSettings& s, uint64_t limit) {
  const FieldProgram* source = colorSourceOf(field, s);
  if (!source || (limit != 0 && 2 * colorWalkLoopEstimate(*source) + 64 >= limit)) return 0;
  const size_t table = source->ops.size() + source->primitiveCount() + 1 + source->maps.size();
  return table + (field.colors ? fieldProgramsShape(*field.colors).poolWords : 0);
}

// Prepares a frame of field under s for loop limit limit (no device): what recordFrame records.
Result<FramePrep> prepareFrame(const GpuField& field, const GpuPolygonizeSettings& s, uint64_t limit,
                               bool conservative) {
  if (!field.a) return Error{"GPU polygoniser: no field program"};
  if (s.resolution < 2 || s.resolution > 512)
    return Error{"GPU polygoniser: resolution " + std::to_string(s.resolution) + " is out of range (2..512)"};
  FramePrep p;
  Result<Grid> grid = makeGrid(field, s);
  if (!grid) return Error{grid.error()};
  p.g = *grid;
  Result<PackedFieldPrograms> packed = packFieldPrograms(*field.a, field.b);
  if (!packed) return Error{"GPU polygoniser: " + packed.error()};
  p.pk = std::move(*packed);
  p.lists = useRegionLists(field, s, limit);
  p.conservative = conservative;
  if (p.lists) {
    // The programs specialised on the CPU per region (gpu_region_op_lists.h).
    const auto t0 = std::chrono::steady_clock::now();
    Result<FrameRegions> built = buildRegionLists(field, p.g, limit, s.loopBudgetCheck, conservative, p.pk);
    if (!built) return Error{"GPU polygoniser: " + built.error()};
    p.fr = std::move(*built);
    p.regionListMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  if (Status c = prepareColors(field, s, limit, p); !c) return Error{c.error()};
  return p;
}

// The most vkCmdUpdateBuffer takes in one call. Larger uploads (the program pool and the
// primitives' bounds: megabytes for the animorphosis demo's C(t)) go through a staging buffer.
constexpr VkDeviceSize kUpdateBufferMax = 65536;

// vkCmdUpdateBuffer in chunks of at most 64 KiB.
void updateBuffer(VkCommandBuffer cmd, VkBuffer buffer, const void* data, VkDeviceSize bytes) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (VkDeviceSize off = 0; off < bytes; off += 65536) {
    VkDeviceSize n = std::min<VkDeviceSize>(65536, bytes - off);
    vkCmdUpdateBuffer(cmd, buffer, off, n, p + off);
  }
}

}  // namespace

// What a prepared frame holds: the field and settings it was prepared for, and its host half.
struct GpuPreparedFrame::Data {
  GpuField field;
  GpuPolygonizeSettings settings;
  uint64_t loopLimit = 0;
  FramePrep prep;
  double milliseconds = 0.0;
  uint64_t id = 0;          // unique among prepared frames
  uint64_t previousId = 0;  // the frame the change bounds are from (0: none)
  std::vector<float> blockBounds;  // per block: how far the field moved since that frame (empty: none)
};

GpuPreparedFrame::GpuPreparedFrame(std::unique_ptr<Data> d) : d_(std::move(d)) {}
GpuPreparedFrame::~GpuPreparedFrame() = default;
double GpuPreparedFrame::milliseconds() const { return d_->milliseconds; }
bool GpuPreparedFrame::hasChangeBounds() const { return !d_->blockBounds.empty(); }

namespace {

std::atomic<uint64_t> gPreparedIds{0};

bool sameGrid(const Grid& a, const Grid& b) {
  return a.origin == b.origin && a.h == b.h && a.n[0] == b.n[0] && a.n[1] == b.n[1] && a.n[2] == b.n[2];
}

// Sum of bounds over the sorted ids of x and of y, each id once.
double sumOverUnion(const std::vector<float>& bounds, const std::vector<uint32_t>& x, const std::vector<uint32_t>* y) {
  double sum = 0.0;
  size_t i = 0, j = 0;
  const size_t ny = y ? y->size() : 0;
  while (i < x.size() || j < ny) {
    uint32_t id;
    if (j >= ny || (i < x.size() && x[i] < (*y)[j])) id = x[i++];
    else if (i >= x.size() || (*y)[j] < x[i]) id = (*y)[j++];
    else { id = x[i++]; ++j; }
    if (id < bounds.size()) sum += double(bounds[id]);
  }
  return sum;
}

// Per block of now's grid: a bound on how far the field moved there since prev (the change bounds
// of the primitives reaching its region -- the finest of the frames' region lists -- in either frame, summed over the programs, plus float
// rounding), the CPU's rule (poly/program_change.h). Empty where no bound holds: another grid,
// structure or morph parameters.
std::vector<float> blockChangeBounds(const GpuField& field, const FramePrep& now, const GpuField& pf,
                                     const FramePrep& prevPrep) {
  if (!sameGrid(now.g, prevPrep.g) || !pf.a || (field.b == nullptr) != (pf.b == nullptr)) return {};
  if (field.b && (field.method != pf.method || field.weight != pf.weight || field.morphTime != pf.morphTime ||
                  field.timeScale != pf.timeScale || field.a0 != pf.a0 || field.a1 != pf.a1 || field.a2 != pf.a2 ||
                  field.a3 != pf.a3))
    return {};
  const FieldProgram* nowP[2] = {field.a, field.b};
  const FieldProgram* prevP[2] = {pf.a, pf.b};
  std::vector<float> change[2];
  float T = 0.0f;
  for (int k = 0; k < 2 && nowP[k]; ++k) {
    if (!sameStructure(*nowP[k], *prevP[k])) return {};
    change[k] = primitiveChangeBounds(*nowP[k], *prevP[k]);
    T = std::max(T, std::abs(nowP[k]->threshold));
  }
  const Grid& g = now.g;
  // The finest regions both frames have lists for: the blocks' (cubes of 2^shift blocks) when they
  // match, else the superblocks'.
  const bool lists = now.lists && prevPrep.lists;
  const bool fine = lists && now.fr.shift == prevPrep.fr.shift && now.fr.dims == prevPrep.fr.dims;
  const RegionOpLists* nowL = fine ? &now.fr.blocks : &now.fr.super;
  const RegionOpLists* prevL = fine ? &prevPrep.fr.blocks : &prevPrep.fr.super;
  const uint32_t shift = fine ? now.fr.shift : 2u;
  const glm::uvec3 dims = fine ? now.fr.dims : glm::uvec3(g.superAxis(0), g.superAxis(1), g.superAxis(2));
  const uint32_t nRegions = dims.x * dims.y * dims.z;
  std::vector<double> perRegion(nRegions, 0.0);
  for (int k = 0; k < 2 && nowP[k]; ++k) {
    const bool have = lists && nowL->reaching[k].size() == nRegions && prevL->reaching[k].size() == nRegions;
    if (!have) {
      double all = 0.0;
      for (float c : change[k]) all += double(c);
      for (double& v : perRegion) v += all;
      continue;
    }
    for (uint32_t r = 0; r < nRegions; ++r)
      perRegion[r] += sumOverUnion(change[k], nowL->reaching[k][r], &prevL->reaching[k][r]);
  }
  std::vector<float> out(g.blocks());
  const float safety = 1e-5f * T;  // float rounding of the evaluations (the CPU's keepsBlock)
  for (uint32_t z = 0; z < g.nb[2]; ++z)
    for (uint32_t y = 0; y < g.nb[1]; ++y)
      for (uint32_t x = 0; x < g.nb[0]; ++x) {
        const uint32_t r = (x >> shift) + dims.x * ((y >> shift) + dims.y * (z >> shift));
        const double v = perRegion[r];
        out[x + g.nb[0] * (y + g.nb[1] * z)] =
            v == 0.0 ? 0.0f : (std::isfinite(v) && v < 1e30 ? float(v) + safety : std::numeric_limits<float>::infinity());
      }
  return out;
}

// How a record walked the programs: per-region lists, built conservatively (single blocks), the
// normals one vertex a dispatch.
struct SlotWalk {
  bool lists = false, conservative = false, normalsPerVertex = false;
};

// Whether a record whose loops the device cut (overflow: its AM_CTL_OVERFLOW bits) can be redone
// sparing the device more: it walked lists, and every pass cut has a sparer form it did not use
// (the coarse and cells passes single-block lists, the normals pass those or one vertex a dispatch).
// A cut colour pass, or a cut frame without lists, cannot.
bool cutFrameRedoable(uint32_t overflow, SlotWalk w) {
  const bool fieldCut = (overflow & (AM_OVERFLOW_CUT_COARSE | AM_OVERFLOW_CUT_CELLS)) != 0;
  const bool normalsCut = (overflow & AM_OVERFLOW_CUT_NORMALS) != 0;
  if (!w.lists || (overflow & AM_OVERFLOW_CUT_COLORS) || (!fieldCut && !normalsCut)) return false;
  if (fieldCut && w.conservative) return false;
  return !normalsCut || !w.conservative || !w.normalsPerVertex;
}

}  // namespace

struct GpuPolygonizer::Impl {
  Context& ctx;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  // The field passes per variant, created on first use or prewarmed (field_pipeline_cache.h).
  using VariantKey = FieldVariantKey;
  FieldPipelineCache fieldCache{[this](const VariantKey& k) {
    return createFieldPipelines(std::get<0>(k), std::get<1>(k), std::get<2>(k) != 0);
  }};
  VkPipeline scan = VK_NULL_HANDLE, scanSingle = VK_NULL_HANDLE, compact = VK_NULL_HANDLE, args = VK_NULL_HANDLE;
  VkPipeline noise = VK_NULL_HANDLE;  // solid-noise displacement (poly_noise.comp)
  // The colour pass (poly_color[_ssbo].comp, generic: not specialised, made on first use); colorPass: this frame's
  // (null: the program has no colours, the mesh keeps its one tone).
  VkPipeline colorUniform = VK_NULL_HANDLE, colorStorage = VK_NULL_HANDLE, colorPass = VK_NULL_HANDLE;
  // The colour pass's pipelines being compiled by prewarm() (index: storage pool 0/1).
  std::array<std::future<Result<VkPipeline>>, 2> colorCompiling;
  // The colour pass's pipeline for the pool kind: made, taken over from prewarm() (waiting for it),
  // or created now (madeHere: true).
  Result<VkPipeline> colorPipeline(bool storage, bool& madeHere);
  // Starts compiling it on a background thread unless it exists or is under way.
  void prewarmColorPipeline(bool storage);
  bool colorPipelineReady(bool storage) const;
  ColorProgramWalk colorWalkThisFrame;  // with colorPass: a colour program's walk (opBegin 0: program A's)
  VkCommandPool commandPool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkQueryPool timestamps = VK_NULL_HANDLE;  // kTimestamps per frame of polygonize(); null when unsupported

  Buffer params, pool, bounds, table, blockMask, blockFlag, blockPrefix, blockSlot, partials, control;
  Buffer superFlag;
  // Temporal coherence: per block of the grid, its kept corners and their record (stamp, bound
  // accumulated since, smallest |f|), and this frame's change bounds (poly_cells_main.glsl).
  Buffer keptCorners, keptInfo, reuseBound;
  uint32_t frameStamp = 1;      // the frames' stamps: +1 to a frame that may reuse, +2 otherwise
  uint64_t lastRecordedId = 0;  // the prepared frame last recorded (0: an unprepared one)
  bool clearKept = true;        // keptInfo was (re)made: zero it before this frame's passes
  const std::vector<float>* frameBounds = nullptr;  // this frame's change bounds to upload (recordPasses)
  Buffer active, corners, edges, counts, offsets;  // per active-block slot
  Buffer positions, normals, indices;
  Buffer readback;  // host: AM_CTL_READBACK_UINTS per frame slot
  // Host buffers per read-back slot: a frame's pool and bounds when they exceed kUpdateBufferMax,
  // copied by the frame's command buffer (vkCmdUpdateBuffer would copy them into the command buffer
  // in 64 KiB pieces). A slot's buffer is rewritten only once its previous frame has completed
  // (record()'s contract; polygonize() waits for its own).
  std::array<Buffer, kFramesInFlight + 1> staging{};
  uint32_t blockCapacity = 0, vertexCapacity = 0, triangleCapacity = 0;
  bool setDirty = true;
  bool uniformPoolAllowed = true;
  std::array<uint64_t, kFramesInFlight + 1> slotSerial{};  // serial whose counters each readback slot holds
  uint64_t syncSerial = 0;  // serials of polygonize(), far from the editor's
  bool haveMesh = false;
  // The counters of a record said its loops were cut (AM_OVERFLOW_LOOPS): the next record() fails
  // with it too, even when recordFitted() took those counters, so the caller goes to the CPU rather
  // than redoing a frame that cannot fit.
  bool cutLoops = false;
  uint32_t cutLoopsBits = 0;  // its AM_CTL_OVERFLOW bits (which passes)
  // How each readback slot's record walked the programs (record): whether a frame of it whose
  // loops were cut can be redone sparing the device more (cutFrameRedoable), as polygonize() does.
  std::array<SlotWalk, kFramesInFlight + 1> slotWalk{};
  uint64_t cutFramesRedone = 0;  // records cut that the next record redid (GpuPolygonizer::cutFramesRedone)
  bool normalsPerVertex = false;  // this frame's normals pass runs once per vertex (recordPasses)
  // A frame walking region lists had the normals pass's loops cut: from then on that pass runs once
  // per vertex wherever lists are walked (the estimates undercount), and polygonize() redoes the frame.
  bool conservativeNormals = false;
  // A frame walking per-region lists had its loops cut all the same (the iteration counts are
  // estimates): from then on the lists are for single blocks and superblocks are not tested as a
  // whole (buildRegionLists), the most the device can be spared. lastRegionLists: the last
  // recorded frame used lists, not yet conservative ones.
  bool conservativeRegions = false, lastRegionLists = false;
  GpuPolygonizeSettings lastSettings;
  Grid lastGrid;

  explicit Impl(Context& c) : ctx(c) { slotSerial.fill(UINT64_MAX); }
  ~Impl();
  Status init();
  Result<VkPipeline> pipeline(const char* name, const VkSpecializationInfo* spec = nullptr);
  // Creates a variant's pipelines (any thread: it touches only the device and the layout).
  Result<FieldPipelines> createFieldPipelines(uint32_t features, uint32_t kinds, bool storage);
  // The variant (specialisation constants, pool buffer kind) programs of this shape (features, kinds,
  // pool size: fieldProgramsShape, or a PackedFieldPrograms') of field need under s.
  VariantKey variantKey(const FieldProgramsShape& shape, const GpuField& field, const GpuPolygonizeSettings& s) const;
  VariantKey variantKey(const PackedFieldPrograms& pk, const GpuField& field, const GpuPolygonizeSettings& s) const {
    return variantKey(FieldProgramsShape{pk.features, pk.kinds, pk.pool.size()}, field, s);
  }
  static uint32_t combineMode(const GpuField& field) {
    return !field.b ? AM_COMBINE_SINGLE
                    : field.method == MorphMethod::Interpolation ? AM_COMBINE_INTERPOLATE : AM_COMBINE_SPACETIME;
  }
  Status ensure(Buffer& b, VkDeviceSize bytes, VkBufferUsageFlags usage);
  Status ensureCapacities(uint32_t blocksWanted, uint32_t verticesWanted, uint32_t trianglesWanted);
  Status ensureStaging(uint32_t slot, VkDeviceSize bytes);
  // The frame's pool and bounds into their device buffers: vkCmdUpdateBuffer when small, else a
  // copy from the slot's staging buffer (ensureStaging first).
  void uploadPrograms(VkCommandBuffer cb, uint32_t slot, const PackedFieldPrograms& pk);
  void writeSet();
  Status recordFrame(VkCommandBuffer cmd, uint32_t slot, const GpuField& field, const GpuPolygonizeSettings& s,
                     GpuPolygonizeStats& stats, bool timed = false, const GpuPreparedFrame* prepared = nullptr);
  // prepared's host half when it suits field under s on this device now (GpuPreparedFrame), else null.
  const FramePrep* usable(const GpuPreparedFrame* prepared, const GpuField& field, const GpuPolygonizeSettings& s) const;
  uint64_t preparesInRecord = 0;
  // Temporal coherence for this frame: the kept buffers sized for grid g (when they fit), the
  // stamp, and the bounds when prepared (a frame prepared against the one recorded last). Returns
  // the stamp (0: nothing kept this frame).
  uint32_t coherence(const Grid& g, const GpuPreparedFrame* prepared, const FramePrep* prep,
                     const GpuPolygonizeSettings& s, GpuPolygonizeStats& stats);
  // recordFrame's parts. The per-frame buffers sized for grid g and programs pk (words: mask words
  // per block), the descriptor set written; fails when a buffer cannot grow or the blocks exceed
  // the scan's limit.
  Status prepareFrameBuffers(const Grid& g, const PackedFieldPrograms& pk, uint32_t words);
  // The passes' parameters for grid g, programs pk and field under s.
  PolyParams frameParams(const Grid& g, const PackedFieldPrograms& pk, const GpuField& field,
                         const GpuPolygonizeSettings& s, uint32_t words) const;
  // A scan of n entries of source (blocks or counts) and what follows it (compaction and/or the
  // indirect arguments): one workgroup when short enough, else three scan phases and the helpers.
  void recordScan(VkCommandBuffer cb, const GpuPolygonizeSettings& s, uint32_t source, uint32_t n, uint32_t nBlocks);
  // The passes: upload, coarse culling, block scan, cells, count scan, emit, normals (and noise),
  // then the counters' copy into readback slot; a timestamp between stages when timed.
  void recordPasses(VkCommandBuffer cb, uint32_t slot, const FieldPipelines& fp, const PolyParams& prm,
                    const PackedFieldPrograms& pk, const Grid& g, const GpuPolygonizeSettings& s, bool timed);
};

GpuPolygonizer::Impl::~Impl() {
  VkDevice dev = ctx.device();
  fieldCache.finishCompiling();  // let background compilations finish, then destroy what they made
  for (bool storage : {false, true}) {
    bool unused = false;
    if (colorCompiling[storage].valid()) (void)colorPipeline(storage, unused);
  }
  vkDeviceWaitIdle(dev);
  for (Buffer* b : {&params, &pool, &bounds, &table, &blockMask, &blockFlag, &blockPrefix, &blockSlot, &partials,
                    &superFlag, &keptCorners, &keptInfo, &reuseBound, &control, &active, &corners, &edges, &counts, &offsets, &positions, &normals, &indices, &readback})
    destroyBuffer(dev, *b);
  for (Buffer& b : staging) destroyBuffer(dev, b);
  fieldCache.destroy(dev);
  for (VkPipeline p : {scan, scanSingle, compact, args, noise, colorUniform, colorStorage})
    if (p) vkDestroyPipeline(dev, p, nullptr);
  if (fence) vkDestroyFence(dev, fence, nullptr);
  if (timestamps) vkDestroyQueryPool(dev, timestamps, nullptr);
  if (commandPool) vkDestroyCommandPool(dev, commandPool, nullptr);
  if (descriptorPool) vkDestroyDescriptorPool(dev, descriptorPool, nullptr);
  if (layout) vkDestroyPipelineLayout(dev, layout, nullptr);
  if (setLayout) vkDestroyDescriptorSetLayout(dev, setLayout, nullptr);
}

Result<VkPipeline> GpuPolygonizer::Impl::pipeline(const char* name, const VkSpecializationInfo* spec) {
  Result<VkShaderModule> module = createShaderModule(ctx.device(), name);
  if (!module) return Error{module.error()};
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, *module,
              "main", spec};
  ci.layout = layout;
  VkPipeline p = VK_NULL_HANDLE;
  VkResult r = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p);
  vkDestroyShaderModule(ctx.device(), *module, nullptr);
  if (r != VK_SUCCESS) return vkError(std::string("compute pipeline ") + name, r);
  return p;
}

Status GpuPolygonizer::Impl::init() {
  VkDevice dev = ctx.device();
  std::array<VkDescriptorSetLayoutBinding, AM_PB_COUNT> b{};
  for (uint32_t i = 0; i < AM_PB_COUNT; ++i) {
    bool uniform = i == AM_PB_POOL_UBO;
    b[i] = {i, uniform ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
            VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  }
  VkDescriptorSetLayoutCreateInfo sli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  sli.bindingCount = AM_PB_COUNT;
  sli.pBindings = b.data();
  AM_VK_TRY(vkCreateDescriptorSetLayout(dev, &sli, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 16};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &push;
  AM_VK_TRY(vkCreatePipelineLayout(dev, &pli, nullptr, &layout), "vkCreatePipelineLayout");
  VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, AM_PB_COUNT}};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = 1;
  dpi.poolSizeCount = 2;
  dpi.pPoolSizes = sizes;
  AM_VK_TRY(vkCreateDescriptorPool(dev, &dpi, nullptr, &descriptorPool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = descriptorPool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &setLayout;
  AM_VK_TRY(vkAllocateDescriptorSets(dev, &ai, &set), "vkAllocateDescriptorSets");

  struct Want {
    VkPipeline* out;
    const char* name;
  } wants[] = {{&scan, "poly_scan.comp"},
               {&scanSingle, "poly_scan_single.comp"},
               {&compact, "poly_compact.comp"},
               {&args, "poly_args.comp"},
               {&noise, "poly_noise.comp"}};
  for (const Want& w : wants) {
    Result<VkPipeline> p = pipeline(w.name);
    if (!p) return Error{p.error()};
    *w.out = *p;
  }

  if (Status c = createCommandResources(dev, ctx.queueFamily(), 1, &commandPool, &cmd, &fence); !c) return Error{c.error()};
  if (ctx.properties().limits.timestampComputeAndGraphics && ctx.properties().limits.timestampPeriod > 0.0f) {
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = kTimestamps;
    if (vkCreateQueryPool(dev, &qi, nullptr, &timestamps) != VK_SUCCESS) timestamps = VK_NULL_HANDLE;
  }

  // A uniform pool suits GPUs; lavapipe specialises shaders on uniform-buffer
  // contents (recompiling as they change) and measured ~10% faster with storage.
  uniformPoolAllowed = ctx.properties().limits.maxUniformBufferRange >= AM_POLY_UNIFORM_POOL_VEC4 * 16u &&
                       ctx.deviceType() != VK_PHYSICAL_DEVICE_TYPE_CPU;
  const VkBufferUsageFlags ssbo = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  Status s = ensure(params, sizeof(PolyParams), ssbo);
  if (s) s = ensure(pool, AM_POLY_UNIFORM_POOL_VEC4 * 16, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | ssbo);
  if (s) s = ensure(bounds, 4096, ssbo);
  if (s) s = ensure(partials, AM_POLY_SCAN_MAX_GROUPS * 8, ssbo);
  if (s) s = ensure(control, AM_CTL_UINTS * 4,
                    ssbo | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  if (s) s = ensure(blockMask, 4096, ssbo);
  if (s) s = ensure(blockFlag, 4096, ssbo);
  if (s) s = ensure(blockPrefix, 4096, ssbo);
  if (s) s = ensure(blockSlot, 4096, ssbo);
  if (s) s = ensure(superFlag, 4096, ssbo);
  if (s) s = ensure(keptCorners, 256, ssbo);
  if (s) s = ensure(keptInfo, 256, ssbo);
  if (s) s = ensure(reuseBound, 256, ssbo);
  if (s) s = ensureCapacities(64, 4096, 8192);
  if (!s) return s;
  Result<Buffer> rb = createHostBuffer(ctx, (kFramesInFlight + 1) * AM_CTL_READBACK_UINTS * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  if (!rb) return Error{"counter read-back buffer: " + rb.error()};
  readback = *rb;
  std::memset(readback.mapped, 0, readback.size);

  // The marching-cubes table, once.
  const MarchingCubesTable& mc = marchingCubesTable();
  std::vector<glm::uvec4> tableData(kTableVec4, glm::uvec4(0u));
  for (int c = 0; c < 256; ++c) {
    for (int k = 0; k < 3 * mc.triangleCount[size_t(c)]; ++k) {
      const int e = mc.triangles[size_t(c)][size_t(k)];
      const uint32_t resolved = uint32_t(mc.edgeCorners[size_t(e)][0]) | uint32_t(mc.edgeAxis[size_t(e)]) << 3;
      const int tri = k / 3, q = k % 3;
      tableData[size_t(c)][tri / 2] |= resolved << (15 * (tri % 2) + 5 * q);
    }
    tableData[size_t(c)].w = uint32_t(mc.triangleCount[size_t(c)]);
  }
  // Then the solid noise's permutation, 256 uints (poly_noise.comp.glsl: in a buffer, a load a
  // lookup; as a constant array in the shader lavapipe's compiler evaluated all 256 entries at
  // every lookup, and the pass took ~170 ms at 96^3 instead of well under 1).
  const uint8_t* perm = solidNoisePermutation();
  for (int i = 0; i < 256; ++i) tableData[256 + size_t(i / 4)][i % 4] = perm[i];
  Result<Buffer> tb = createDeviceBuffer(ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, tableData.data(),
                                         tableData.size() * sizeof(glm::uvec4));
  if (!tb) return Error{"marching-cubes table: " + tb.error()};
  table = *tb;
  return Status::success();
}

GpuPolygonizer::Impl::VariantKey GpuPolygonizer::Impl::variantKey(const FieldProgramsShape& pk, const GpuField& field,
                                                                  const GpuPolygonizeSettings& s) const {
  const bool fitsUniform = pk.poolWords <= AM_POLY_UNIFORM_POOL_VEC4 &&
                           ctx.properties().limits.maxUniformBufferRange >= AM_POLY_UNIFORM_POOL_VEC4 * 16u;
  // Per-region lists make the pool grow with the grid: always a storage buffer (prewarm() and
  // ready() pack the programs without them and must pick the same variant).
  const bool lists = useRegionLists(field, s, loopLimit(ctx.properties()));
  const bool storagePool = s.poolBuffer == GpuPolygonizeSettings::PoolBuffer::Storage || !fitsUniform || lists ||
                           (s.poolBuffer == GpuPolygonizeSettings::PoolBuffer::Auto && !uniformPoolAllowed);
  const uint32_t features = s.specialise ? pk.features | AM_FEAT_COMBINE_BIT(combineMode(field)) : AM_FEAT_ALL;
  const uint32_t kinds = s.specialise ? pk.kinds : AM_FEAT_ALL;
  return {features, kinds, storagePool ? 1 : 0};
}

Result<FieldPipelines> GpuPolygonizer::Impl::createFieldPipelines(uint32_t features,
                                                                                         uint32_t kinds, bool storage) {
  const uint32_t values[2] = {features, kinds};
  const VkSpecializationMapEntry entries[2] = {{0, 0, 4}, {1, 4, 4}};
  VkSpecializationInfo spec{2, entries, sizeof values, values};
  FieldPipelines v;
  struct Want {
    VkPipeline* out;
    const char* name;
  } wants[] = {{&v.blocks, storage ? "poly_blocks_ssbo.comp" : "poly_blocks.comp"},
               {&v.cells, storage ? "poly_cells_ssbo.comp" : "poly_cells.comp"},
               {&v.emit, storage ? "poly_emit_ssbo.comp" : "poly_emit.comp"},
               {&v.normals, storage ? "poly_normals_ssbo.comp" : "poly_normals.comp"}};
  for (const Want& w : wants) {
    Result<VkPipeline> p = pipeline(w.name, &spec);
    if (!p) {
      for (VkPipeline made : {v.blocks, v.cells, v.emit, v.normals})
        if (made) vkDestroyPipeline(ctx.device(), made, nullptr);
      return Error{p.error()};
    }
    *w.out = *p;
  }
  return v;
}

Status GpuPolygonizer::Impl::ensure(Buffer& b, VkDeviceSize bytes, VkBufferUsageFlags usage) {
  if (b.buffer && b.size >= bytes) return Status::success();
  const VkDeviceSize limit = ctx.properties().limits.maxStorageBufferRange;
  VkDeviceSize size = roundCapacity(bytes);
  if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && size > limit) size = std::max(bytes, VkDeviceSize(limit));
  if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && bytes > limit)
    return Error{"GPU polygoniser: a buffer of " + std::to_string(bytes) + " bytes exceeds the device's storage-buffer limit of " +
                 std::to_string(limit) + " bytes (lower the resolution)"};
  if (b.buffer) {
    vkDeviceWaitIdle(ctx.device());  // rare: only when a frame outgrows a buffer
    destroyBuffer(ctx.device(), b);
  }
  Result<Buffer> nb = createBuffer(ctx, size, usage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (!nb) return Error{"GPU polygoniser: " + nb.error()};
  b = *nb;
  setDirty = true;
  return Status::success();
}

Status GpuPolygonizer::Impl::ensureCapacities(uint32_t blocksWanted, uint32_t verticesWanted, uint32_t trianglesWanted) {
  const VkBufferUsageFlags ssbo = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  const VkBufferUsageFlags readable = ssbo | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  blocksWanted = std::max(blocksWanted, 1u);
  verticesWanted = std::max(verticesWanted, 3u);
  trianglesWanted = std::max(trianglesWanted, 1u);
  Status s = Status::success();
  if (blocksWanted > blockCapacity) {
    s = ensure(active, VkDeviceSize(blocksWanted) * 4, ssbo);
    if (s) s = ensure(corners, VkDeviceSize(blocksWanted) * AM_POLY_BLOCK_CORNERS * 4, ssbo);
    if (s) s = ensure(edges, VkDeviceSize(blocksWanted) * AM_POLY_EDGE_INFO * 4, ssbo);
    if (s) s = ensure(counts, VkDeviceSize(blocksWanted) * 8, ssbo);
    if (s) s = ensure(offsets, VkDeviceSize(blocksWanted) * 8, ssbo);
    if (!s) return s;
    blockCapacity = blocksWanted;
  }
  if (verticesWanted > vertexCapacity) {
    s = ensure(positions, VkDeviceSize(verticesWanted) * kVertexStride, readable | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    if (s) s = ensure(normals, VkDeviceSize(verticesWanted) * kVertexStride, readable | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    if (!s) return s;
    vertexCapacity = verticesWanted;
  }
  if (trianglesWanted > triangleCapacity) {
    s = ensure(indices, VkDeviceSize(trianglesWanted) * 12, readable | VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    if (!s) return s;
    triangleCapacity = trianglesWanted;
  }
  return s;
}

Status GpuPolygonizer::Impl::ensureStaging(uint32_t slot, VkDeviceSize bytes) {
  Buffer& b = staging[slot];
  if (b.buffer && b.size >= bytes) return Status::success();
  destroyBuffer(ctx.device(), b);  // its last frame has completed
  Result<Buffer> nb = createHostBuffer(ctx, roundCapacity(bytes), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  if (!nb) return Error{"GPU polygoniser: staging buffer: " + nb.error()};
  b = *nb;
  return Status::success();
}

void GpuPolygonizer::Impl::uploadPrograms(VkCommandBuffer cb, uint32_t slot, const PackedFieldPrograms& pk) {
  const VkDeviceSize poolBytes = pk.pool.size() * 16, boundsBytes = pk.bounds.size() * 16;
  if (poolBytes + boundsBytes <= kUpdateBufferMax) {
    updateBuffer(cb, pool.buffer, pk.pool.data(), poolBytes);
    updateBuffer(cb, bounds.buffer, pk.bounds.data(), boundsBytes);
    return;
  }
  auto* host = static_cast<uint8_t*>(staging[slot].mapped);  // host-coherent: visible at the submit
  std::memcpy(host, pk.pool.data(), poolBytes);
  std::memcpy(host + poolBytes, pk.bounds.data(), boundsBytes);
  const VkBufferCopy toPool{0, 0, poolBytes}, toBounds{poolBytes, 0, boundsBytes};
  vkCmdCopyBuffer(cb, staging[slot].buffer, pool.buffer, 1, &toPool);
  vkCmdCopyBuffer(cb, staging[slot].buffer, bounds.buffer, 1, &toBounds);
}

void GpuPolygonizer::Impl::writeSet() {
  if (!setDirty) return;
  std::array<VkDescriptorBufferInfo, AM_PB_COUNT> info{};
  auto whole = [](const Buffer& b) { return VkDescriptorBufferInfo{b.buffer, 0, VK_WHOLE_SIZE}; };
  info[AM_PB_PARAMS] = {params.buffer, 0, sizeof(PolyParams)};
  const VkDeviceSize uboRange =
      std::min<VkDeviceSize>(AM_POLY_UNIFORM_POOL_VEC4 * 16, ctx.properties().limits.maxUniformBufferRange);
  info[AM_PB_POOL_UBO] = {pool.buffer, 0, uboRange};
  info[AM_PB_POOL_SSBO] = whole(pool);
  info[AM_PB_BOUNDS] = whole(bounds);
  info[AM_PB_TABLE] = {table.buffer, 0, kTableVec4 * 16};
  info[AM_PB_BLOCK_MASK] = whole(blockMask);
  info[AM_PB_BLOCK_FLAG] = whole(blockFlag);
  info[AM_PB_BLOCK_PREFIX] = whole(blockPrefix);
  info[AM_PB_BLOCK_SLOT] = whole(blockSlot);
  info[AM_PB_SUPER_FLAG] = whole(superFlag);
  info[AM_PB_KEPT_CORNERS] = whole(keptCorners);
  info[AM_PB_KEPT_INFO] = whole(keptInfo);
  info[AM_PB_REUSE_BOUND] = whole(reuseBound);
  info[AM_PB_ACTIVE] = whole(active);
  info[AM_PB_CORNERS] = whole(corners);
  info[AM_PB_EDGES] = whole(edges);
  info[AM_PB_COUNTS] = whole(counts);
  info[AM_PB_OFFSETS] = whole(offsets);
  info[AM_PB_PARTIALS] = whole(partials);
  info[AM_PB_CONTROL] = whole(control);
  info[AM_PB_POSITIONS] = whole(positions);
  info[AM_PB_NORMALS] = whole(normals);
  info[AM_PB_INDICES] = whole(indices);
  std::array<VkWriteDescriptorSet, AM_PB_COUNT> w{};
  for (uint32_t i = 0; i < AM_PB_COUNT; ++i) {
    bool uniform = i == AM_PB_POOL_UBO;
    w[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, i, 0, 1,
            uniform ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &info[i], nullptr};
  }
  vkUpdateDescriptorSets(ctx.device(), AM_PB_COUNT, w.data(), 0, nullptr);
  setDirty = false;
}

Status GpuPolygonizer::Impl::prepareFrameBuffers(const Grid& g, const PackedFieldPrograms& pk, uint32_t words) {
  const uint32_t nBlocks = g.blocks();
  const VkBufferUsageFlags ssbo = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  Status st = ensure(pool, std::max<VkDeviceSize>(AM_POLY_UNIFORM_POOL_VEC4 * 16, pk.pool.size() * 16),
                     VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | ssbo);
  if (st) st = ensure(bounds, pk.bounds.size() * 16, ssbo);
  const uint32_t nSuper = g.superBlocks();
  if (st) st = ensure(blockMask, VkDeviceSize(nBlocks + nSuper) * words * 4, ssbo);
  if (st) st = ensure(blockFlag, VkDeviceSize(nBlocks) * 8, ssbo);
  if (st) st = ensure(blockPrefix, VkDeviceSize(nBlocks) * 8, ssbo);
  if (st) st = ensure(blockSlot, VkDeviceSize(nBlocks) * 4, ssbo);
  if (st) st = ensure(superFlag, VkDeviceSize(nSuper) * 4, ssbo);
  if (!st) return st;
  if (nBlocks > AM_POLY_SCAN_PER_GROUP * AM_POLY_SCAN_MAX_GROUPS)
    return Error{"GPU polygoniser: " + std::to_string(nBlocks) + " blocks exceed the scan's limit"};
  writeSet();
  return Status::success();
}

PolyParams GpuPolygonizer::Impl::frameParams(const Grid& g, const PackedFieldPrograms& pk, const GpuField& field,
                                             const GpuPolygonizeSettings& s, uint32_t words) const {
  const float Tmax = std::max(pk.threshold[0], pk.programCount > 1 ? pk.threshold[1] : 0.0f);
  PolyParams prm{};
  prm.gridOrigin = glm::vec4(g.origin, g.h);
  const uint32_t rowLimit = std::min<uint32_t>(AM_POLY_MAX_DISPATCH_X, ctx.properties().limits.maxComputeWorkGroupCount[0]);
  prm.gridCells = glm::uvec4(g.n[0], g.n[1], g.n[2], s.dispatchRow ? std::min(s.dispatchRow, rowLimit) : rowLimit);
  prm.gridBlocks = glm::uvec4(g.nb[0], g.nb[1], g.nb[2], g.blocks());
  prm.progA = glm::uvec4(pk.opBegin[0], pk.opCount[0], pk.primBegin[0], pk.primCount[0]);
  prm.progB = glm::uvec4(pk.opBegin[1], pk.opCount[1], pk.primBegin[1], pk.primCount[1]);
  prm.thresholds = glm::vec4(pk.threshold[0], pk.threshold[1], 1e-3f * Tmax + 1e-7f, -1e-6f * Tmax);
  const uint32_t combine = combineMode(field);
  prm.modes = glm::uvec4(combine, words, s.culling ? 1u : 0u, blockCapacity);
  prm.morph0 = glm::vec4(field.weight, field.morphTime, field.timeScale, field.a0);
  const float normalStep = 0.05f * g.h;
  prm.morph1 = glm::vec4(field.a1, field.a2, field.a3, normalStep);
  prm.caps = glm::uvec4(vertexCapacity, triangleCapacity, pk.primitiveTotal(), 1u);
  prm.extra = glm::vec4(2.0f * normalStep, s.noiseAmplitude, s.noiseFrequency, 0.0f);
  prm.superBlocks = glm::uvec4(g.superAxis(0), g.superAxis(1), g.superAxis(2), g.superBlocks());
  return prm;
}

void GpuPolygonizer::Impl::recordScan(VkCommandBuffer cb, const GpuPolygonizeSettings& s, uint32_t source,
                                      uint32_t n, uint32_t nBlocks) {
  auto push = [&](uint32_t x, uint32_t y, uint32_t z) {
    glm::uvec4 pc(x, y, z, 0u);
    vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 16, &pc);
  };
  if (s.singleWorkgroupScan && n <= AM_POLY_SCAN_SINGLE_MAX) {
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, scanSingle);
    push(0, source, n);
    vkCmdDispatch(cb, 1, 1, 1);
    computeToCompute(cb);
    return;
  }
  uint32_t groups = std::max(1u, (n + AM_POLY_SCAN_PER_GROUP - 1) / AM_POLY_SCAN_PER_GROUP);
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, scan);
  push(AM_SCAN_REDUCE, source, n);
  vkCmdDispatch(cb, groups, 1, 1);
  computeToCompute(cb);
  push(AM_SCAN_PARTIALS, source, n);
  vkCmdDispatch(cb, 1, 1, 1);
  computeToCompute(cb);
  push(AM_SCAN_DOWNSWEEP, source, n);
  vkCmdDispatch(cb, groups, 1, 1);
  computeToCompute(cb);
  if (source == AM_SCAN_SOURCE_BLOCKS) {
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, compact);
    vkCmdDispatch(cb, (nBlocks + AM_POLY_WG_LINEAR - 1) / AM_POLY_WG_LINEAR, 1, 1);
    computeToCompute(cb);
  }
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, args);
  push(source == AM_SCAN_SOURCE_BLOCKS ? AM_ARGS_AFTER_BLOCKS : AM_ARGS_AFTER_COUNTS, 0, 0);
  vkCmdDispatch(cb, 1, 1, 1);
  computeToCompute(cb);
}

void GpuPolygonizer::Impl::recordPasses(VkCommandBuffer cb, uint32_t slot, const FieldPipelines& fp,
                                        const PolyParams& prm, const PackedFieldPrograms& pk, const Grid& g,
                                        const GpuPolygonizeSettings& s, bool timed) {
  const uint32_t nBlocks = g.blocks(), nSuper = g.superBlocks();
  uint32_t stamp = 0;
  auto timestamp = [&] {
    if (timed) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, stamp++);
  };
  if (timed) vkCmdResetQueryPool(cb, timestamps, 0, kTimestamps);
  timestamp();
  // This frame's writes wait for the previous frame's readers (draw, copies) and writers.
  barrier(cb,
          VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
          VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
          VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  updateBuffer(cb, params.buffer, &prm, sizeof(prm));
  uploadPrograms(cb, slot, pk);
  vkCmdFillBuffer(cb, control.buffer, 0, AM_CTL_UINTS * 4, 0);
  vkCmdFillBuffer(cb, counts.buffer, 0, VkDeviceSize(blockCapacity) * 8, 0);
  if (clearKept) vkCmdFillBuffer(cb, keptInfo.buffer, 0, VK_WHOLE_SIZE, 0);
  clearKept = false;
  if (frameBounds) updateBuffer(cb, reuseBound.buffer, frameBounds->data(), frameBounds->size() * sizeof(float));
  barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT);

  timestamp();
  vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
  auto push = [&](uint32_t x, uint32_t y, uint32_t z) {
    glm::uvec4 pc(x, y, z, 0u);
    vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 16, &pc);
  };
  const uint32_t linearGroups = (nBlocks + AM_POLY_WG_BLOCKS - 1) / AM_POLY_WG_BLOCKS;
  // Coarse: superblock bounds, then per-block primitive lists and interval culling.
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, fp.blocks);
  if (s.culling) {
    push(AM_COARSE_SUPERBLOCKS, 0, 0);
    vkCmdDispatch(cb, (nSuper + AM_POLY_WG_BLOCKS - 1) / AM_POLY_WG_BLOCKS, 1, 1);
    computeToCompute(cb);
  }
  push(AM_COARSE_BLOCKS, 0, 0);
  vkCmdDispatch(cb, linearGroups, 1, 1);
  computeToCompute(cb);
  timestamp();
  // Active blocks -> slots, and the fine passes' dispatch.
  recordScan(cb, s, AM_SCAN_SOURCE_BLOCKS, nBlocks, nBlocks);
  timestamp();
  // Fine: corner values, cell cases, vertex and triangle counts.
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, fp.cells);
  vkCmdDispatchIndirect(cb, control.buffer, AM_CTL_DISPATCH * 4);
  computeToCompute(cb);
  timestamp();
  // Per-slot offsets, the draw's and the normals pass's arguments.
  recordScan(cb, s, AM_SCAN_SOURCE_COUNTS, blockCapacity, nBlocks);
  timestamp();
  // Vertices and triangles per block, then the normals of all vertices.
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, fp.emit);
  vkCmdDispatchIndirect(cb, control.buffer, AM_CTL_DISPATCH * 4);
  computeToCompute(cb);
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, fp.normals);
  if (normalsPerVertex) {
    // Walking region lists, an invocation's four vertices may lie in two regions (block order), each
    // one more walk of a list (twice for the stencil's two pairs). Near lavapipe's loop limit: one
    // dispatch per vertex of the four, each invocation walking one list once (the limiter counts a
    // SIMD group's iterations per dispatch).
    for (uint32_t k = 0; k < 4; ++k) {
      push(AM_NORMALS_VERTEX + k, 0u, 0u);
      vkCmdDispatchIndirect(cb, control.buffer, AM_CTL_NORMALS * 4);
    }
  } else {
    push(AM_NORMALS_ALL, 0u, 0u);
    vkCmdDispatchIndirect(cb, control.buffer, AM_CTL_NORMALS * 4);
  }
  if (colorPass) {
    const ColorProgramWalk& colorWalk = colorWalkThisFrame;
    // The vertices' colours into the normals' w (poly_color_main.glsl), before the noise moves them
    // (the CPU colours the undisplaced surface): one dispatch per vertex of the normals' four.
    computeToCompute(cb);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, colorPass);
    for (uint32_t k = 0; k < 4; ++k) {
      glm::uvec4 pc(k, colorWalk.opBegin, colorWalk.opCount, 0u);
      std::memcpy(&pc.w, &colorWalk.threshold, 4);
      vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 16, &pc);
      vkCmdDispatchIndirect(cb, control.buffer, AM_CTL_NORMALS * 4);
    }
  }
  if (s.noiseAmplitude != 0.0f) {
    // Solid noise along the normals just made (the CPU's displaceBySolidNoise).
    computeToCompute(cb);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, noise);
    vkCmdDispatchIndirect(cb, control.buffer, AM_CTL_NORMALS * 4);
  }
  barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
          VK_ACCESS_SHADER_WRITE_BIT,
          VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
              VK_ACCESS_TRANSFER_READ_BIT);
  timestamp();
  VkBufferCopy copy{0, VkDeviceSize(slot) * AM_CTL_READBACK_UINTS * 4, AM_CTL_READBACK_UINTS * 4};
  vkCmdCopyBuffer(cb, control.buffer, readback.buffer, 1, &copy);
  barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
          VK_ACCESS_HOST_READ_BIT);
}

uint32_t GpuPolygonizer::Impl::coherence(const Grid& g, const GpuPreparedFrame* prepared, const FramePrep* prep,
                                         const GpuPolygonizeSettings& s, GpuPolygonizeStats& stats) {
  frameBounds = nullptr;
  stats.coherent = false;
  const GpuPreparedFrame::Data* d = prepared && prep == &prepared->d_->prep ? prepared->d_.get() : nullptr;
  const uint64_t recordedBefore = lastRecordedId;
  lastRecordedId = 0;  // (a frame that keeps nothing is no base for the next one's bounds)
  const VkDeviceSize keptBytes = VkDeviceSize(g.blocks()) * AM_POLY_BLOCK_CORNERS * 4;
  const VkDeviceSize cap = std::min<VkDeviceSize>(VkDeviceSize(256) << 20, ctx.properties().limits.maxStorageBufferRange);
  // (an unprepared frame keeps nothing: no later frame's bounds can be from it)
  if (!d || s.reuseToleranceCells < 0.0f || keptBytes > cap) return 0;
  const VkBufferUsageFlags ssbo = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  const VkBuffer infoBefore = keptInfo.buffer, cornersBefore = keptCorners.buffer;
  Status st = ensure(keptCorners, keptBytes, ssbo);
  if (st) st = ensure(keptInfo, VkDeviceSize(g.blocks()) * 16, ssbo);
  if (st) st = ensure(reuseBound, VkDeviceSize(g.blocks()) * 4, ssbo);
  if (keptInfo.buffer != infoBefore || keptCorners.buffer != cornersBefore) clearKept = true;
  if (!st) {  // nothing is kept this frame; small buffers again where one could not grow
    for (Buffer* b : {&keptCorners, &keptInfo, &reuseBound})
      if (!b->buffer) (void)ensure(*b, 256, ssbo);
    writeSet();
    return 0;
  }
  lastRecordedId = d ? d->id : 0;
  writeSet();
  const bool reuse = d && !d->blockBounds.empty() && d->previousId == recordedBefore && !clearKept &&
                     d->blockBounds.size() == g.blocks();
  frameStamp += reuse ? 1u : 2u;
  if (reuse) frameBounds = &d->blockBounds;
  stats.coherent = reuse;
  return frameStamp;
}

Status GpuPolygonizer::Impl::recordFrame(VkCommandBuffer cb, uint32_t slot, const GpuField& field,
                                         const GpuPolygonizeSettings& s, GpuPolygonizeStats& stats, bool timed,
                                         const GpuPreparedFrame* prepared) {
  const uint64_t limit = loopLimit(ctx.properties());
  // The host half: prepared off this thread (GpuPreparedFrame), or here.
  const FramePrep* prep = usable(prepared, field, s);
  std::optional<FramePrep> own;
  stats.preparedInRecord = prep == nullptr;
  stats.prepareMs = 0.0;
  if (!prep) {
    const auto t0 = std::chrono::steady_clock::now();
    Result<FramePrep> made = prepareFrame(field, s, limit, conservativeRegions);
    if (!made) return Error{made.error()};
    own = std::move(*made);
    prep = &*own;
    ++preparesInRecord;
    stats.prepareMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  const Grid& g = prep->g;
  const bool lists = prep->lists;
  const FrameRegions& fr = prep->fr;
  stats.regionLists = lists;
  stats.regionListMs = 0.0;
  if (lists) {
    stats.regionListMs = prep->regionListMs;
    stats.regionLongestOps = fr.blocks.longestOps;
    stats.regionOpsTotal = fr.blocks.opsTotal;
    stats.regionBlocks = 1u << fr.shift;
  }
  // Two regions among an invocation's four vertices, two walks each with the stencil; and twice that
  // again: the walks counted undercount (C(t) of the demo at 2.6 s, 128^3, single-block lists: a
  // walk counted at ~17 900 and one dispatch of the four vertices cut at 65 535).
  const uint64_t oneNormalsDispatch = uint64_t(fr.blocks.stencilNormals ? 4 : 2) * fr.blocks.longestNormalWalk;
  normalsPerVertex =
      lists && (s.normalsPerVertex || conservativeNormals || (limit != 0 && 2 * oneNormalsDispatch + 64 >= limit));
  stats.normalsDispatches = normalsPerVertex ? 4u : 1u;
  lastRegionLists = lists && !conservativeRegions;
  if (s.loopBudgetCheck && !lists)
    if (std::string why = loopBudgetReason(field, limit); !why.empty()) return Error{"GPU polygoniser: " + why};
  const uint32_t colorTable = prep->colorTable;
  const ColorProgramWalk& colorWalk = prep->colorWalk;
  stats.colors = colorTable != 0;
  const PackedFieldPrograms& pk = prep->pk;
  const uint32_t words = std::max(1u, (pk.primitiveTotal() + 31) / 32);
  const VariantKey variant = variantKey(pk, field, s);
  const bool storagePool = std::get<2>(variant) != 0;
  if (Status st = prepareFrameBuffers(g, pk, words); !st) return st;
  if ((pk.pool.size() + pk.bounds.size()) * 16 > kUpdateBufferMax)
    if (Status st = ensureStaging(slot, (pk.pool.size() + pk.bounds.size()) * 16); !st) return st;
  PolyParams prm = frameParams(g, pk, field, s, words);
  // poly_color_main.glsl: the colour table's pool index (0: none), its maps, 1 + the shift of the
  // regions of the lists the pass walks (0: the whole program), the colour program's lists (0: A's).
  prm.colorPass =
      glm::uvec4(colorTable, prep->colorMaps, prep->colorLists ? 1u + prep->colorListShift : 0u, colorWalk.lists);
  stats.colorRegionLists = colorTable != 0 && prep->colorLists;
  stats.colorPipelineMadeInRecord = false;
  colorPass = VK_NULL_HANDLE;
  if (colorTable != 0) {  // prewarmed, or created on first use (on lavapipe a pipeline takes a while to compile)
    Result<VkPipeline> p = colorPipeline(storagePool, stats.colorPipelineMadeInRecord);
    if (!p) return Error{p.error()};
    colorPass = *p;
  }
  colorWalkThisFrame = colorWalk;
  if (lists) {
    prm.regions = glm::uvec4(1u, fr.super.table, fr.super.masks * 4u, fr.shift);
    prm.regionLists = glm::uvec4(fr.blocks.table, fr.dims.x, fr.dims.y, 0u);
  }

  stats.gridX = int(g.n[0]);
  stats.gridY = int(g.n[1]);
  stats.gridZ = int(g.n[2]);
  stats.cellSize = g.h;
  stats.blocksTotal = g.blocks();
  stats.uniformPool = !storagePool;
  stats.features = std::get<0>(variant);
  stats.kinds = std::get<1>(variant);
  Result<FieldPipelines> fp = fieldCache.get({stats.features, stats.kinds, storagePool ? 1 : 0});
  if (!fp) return Error{fp.error()};
  prm.regionLists.w = coherence(g, prepared, prep, s, stats);
  prm.extra.w = s.reuseToleranceCells > 0.0f ? 2.0f * s.reuseToleranceCells / (1.0f + 2.0f * s.reuseToleranceCells) : 0.0f;
  lastGrid = g;
  recordPasses(cb, slot, *fp, prm, pk, g, s, timed && timestamps != VK_NULL_HANDLE);
  frameBounds = nullptr;
  return Status::success();
}

namespace {
// Blocks the buffers are first sized for, out of a grid's nb. A record reads its counters
// kFramesInFlight records later, so a first record that overflows draws nothing for that long
// (the preview would flash empty when it appears). Grids up to 4096 blocks (128^3) get room for
// every block (the preview's bounds hug the shape: the demo morph has 283 of ~900 blocks active
// at 128^3); larger ones a quarter, at least 4096 (~14 KiB a block with its vertices and triangles).
uint32_t firstBlockCapacity(uint32_t nb) { return nb <= 4096u ? nb : std::max(4096u, nb / 4u); }

// A frame whose shaders found their loops cut short (AM_OVERFLOW_LOOPS): nothing of it is drawn.
constexpr const char* kCutLoops =
    "GPU polygoniser: the device cut the shaders' loops short (llvmpipe stops a shader's loops after "
    "65535 iterations): the program is too large for this device; polygonise it on the CPU";

// kCutLoops, naming the passes whose loops were cut (the AM_OVERFLOW_CUT_* bits of overflow).
std::string cutLoopsError(uint32_t overflow) {
  std::string passes;
  for (auto [bit, name] : {std::pair{AM_OVERFLOW_CUT_COARSE, "coarse"}, std::pair{AM_OVERFLOW_CUT_CELLS, "cells"},
                           std::pair{AM_OVERFLOW_CUT_NORMALS, "normals"}, std::pair{AM_OVERFLOW_CUT_COLORS, "colour"}})
    if (overflow & bit) passes += std::string(passes.empty() ? "" : ", ") + name;
  return std::string(kCutLoops) + (passes.empty() ? "" : " (the " + passes + " pass)");
}
}  // namespace

GpuPolygonizer::GpuPolygonizer(Context& ctx) : impl_(std::make_unique<Impl>(ctx)) {}
GpuPolygonizer::~GpuPolygonizer() = default;

std::string GpuPolygonizer::deviceShortfall(const VkPhysicalDeviceLimits& l) {
  const uint32_t largestGroup = std::max({AM_POLY_WG_BLOCKS, AM_POLY_WG_CELLS, AM_POLY_WG_EMIT, AM_POLY_WG_NORMALS,
                                          AM_POLY_WG_SCAN, AM_POLY_WG_LINEAR});
  std::string why;
  auto add = [&](const std::string& s) { why += (why.empty() ? "" : "; ") + s; };
  if (l.maxComputeSharedMemorySize < AM_POLY_EMIT_SHARED_BYTES)
    add("the device has " + std::to_string(l.maxComputeSharedMemorySize) + " bytes of compute shared memory, the emit pass needs " +
        std::to_string(AM_POLY_EMIT_SHARED_BYTES));
  if (l.maxComputeWorkGroupInvocations < largestGroup || l.maxComputeWorkGroupSize[0] < largestGroup)
    add("the device runs at most " + std::to_string(std::min(l.maxComputeWorkGroupInvocations, l.maxComputeWorkGroupSize[0])) +
        " invocations in a workgroup, the scan needs " + std::to_string(largestGroup));
  return why;
}

Result<std::unique_ptr<GpuPolygonizer>> GpuPolygonizer::create(Context& ctx) {
  if (std::string why = deviceShortfall(ctx.properties().limits); !why.empty()) return Error{"GPU polygoniser: " + why};
  std::unique_ptr<GpuPolygonizer> p(new GpuPolygonizer(ctx));
  Status s = p->impl_->init();
  if (!s) return Error{"GPU polygoniser: " + s.error()};
  return p;
}

uint64_t GpuPolygonizer::loopLimit(const VkPhysicalDeviceProperties& p) {
  const bool llvmpipe = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU && std::strstr(p.deviceName, "llvmpipe") != nullptr;
  return llvmpipe ? AM_POLY_LLVMPIPE_LOOP_LIMIT : 0;
}

std::string GpuPolygonizer::unsupported(const GpuField& field) {
  if (!field.a) return "no field program";
  if (field.b && field.method == MorphMethod::SkeletonCorrespondence)
    return "skeleton correspondence combines stand-ins that move with w: polygonise its flattened program "
           "(morphImplicitField) as a single field";
  if (std::string why = gpuUnsupportedReason(*field.a); !why.empty()) return why;
  if (field.b)
    if (std::string why = gpuUnsupportedReason(*field.b); !why.empty()) return "target program: " + why;
  return {};  // a program's size is no reason (regionPrograms): record() and polygonize() check the regions
}

Result<VkPipeline> GpuPolygonizer::Impl::colorPipeline(bool storage, bool& madeHere) {
  VkPipeline& made = storage ? colorStorage : colorUniform;
  std::future<Result<VkPipeline>>& compiling = colorCompiling[storage];
  madeHere = false;
  if (!made && compiling.valid()) {
    Result<VkPipeline> p = compiling.get();  // a failure is not kept: made below, naming the error
    if (p) made = *p;
  }
  if (!made) {
    Result<VkPipeline> p = pipeline(storage ? "poly_color_ssbo.comp" : "poly_color.comp");
    if (!p) return Error{p.error()};
    made = *p;
    madeHere = true;
  }
  return made;
}

void GpuPolygonizer::Impl::prewarmColorPipeline(bool storage) {
  if ((storage ? colorStorage : colorUniform) || colorCompiling[storage].valid()) return;
  const char* name = storage ? "poly_color_ssbo.comp" : "poly_color.comp";
  colorCompiling[storage] = std::async(std::launch::async, [this, name] { return pipeline(name); });
}

bool GpuPolygonizer::Impl::colorPipelineReady(bool storage) const {
  if (storage ? colorStorage : colorUniform) return true;
  const std::future<Result<VkPipeline>>& f = colorCompiling[storage];
  return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

namespace {
// The programs' shape with what the colour pass adds to the pool (colorPoolWords).
FieldProgramsShape framePoolShape(const GpuField& field, const GpuPolygonizeSettings& s, uint64_t limit) {
  FieldProgramsShape shape = fieldProgramsShape(*field.a, field.b);
  shape.poolWords += colorPoolWords(field, s, limit);
  return shape;
}
}  // namespace

void GpuPolygonizer::prewarm(const GpuField& field, const GpuPolygonizeSettings& s) {
  Impl& m = *impl_;
  if (!field.a || !unsupported(field).empty()) return;
  const Impl::VariantKey key = m.variantKey(framePoolShape(field, s, loopLimit(m.ctx.properties())), field, s);
  m.fieldCache.prewarm(key);
  if (colorSourceOf(field, s)) m.prewarmColorPipeline(std::get<2>(key) != 0);
}

bool GpuPolygonizer::ready(const GpuField& field, const GpuPolygonizeSettings& s) const {
  const Impl& m = *impl_;
  if (!field.a || !gpuUnsupportedReason(*field.a).empty() || (field.b && !gpuUnsupportedReason(*field.b).empty()))
    return true;  // record() fails at once
  // The variant from the programs' shape: packing them whole (megabytes for the animorphosis
  // demo's C(t)) only to look the variant up cost as much as the record's own packing, every frame.
  const Impl::VariantKey key = m.variantKey(framePoolShape(field, s, loopLimit(m.ctx.properties())), field, s);
  return m.fieldCache.ready(key) && (!colorSourceOf(field, s) || m.colorPipelineReady(std::get<2>(key) != 0));
}

bool GpuPolygonizer::waitForCompilation(double timeoutSec) const {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSec);
  bool done = impl_->fieldCache.waitForCompilation(timeoutSec);
  for (const auto& f : impl_->colorCompiling)
    if (f.valid()) done = f.wait_until(until) == std::future_status::ready && done;
  return done;
}

size_t GpuPolygonizer::variantCount() const { return impl_->fieldCache.size(); }

Status GpuPolygonizer::absorbCounters(uint32_t slot) {
  Impl& m = *impl_;
  if (m.slotSerial[slot] == UINT64_MAX) return Status::success();  // none, or taken already
  m.slotSerial[slot] = UINT64_MAX;
  const auto* c = static_cast<const uint32_t*>(m.readback.mapped) + slot * AM_CTL_READBACK_UINTS;
  stats_.blocksActive = c[AM_CTL_ACTIVE];
  stats_.vertices = c[AM_CTL_VERTICES];
  stats_.triangles = c[AM_CTL_TRIANGLES];
  stats_.overflowed = c[AM_CTL_OVERFLOW] != 0;
  stats_.blocksReused = c[AM_CTL_REUSED];
  if (c[AM_CTL_OVERFLOW] == 0) return Status::success();
  if (c[AM_CTL_OVERFLOW] & AM_OVERFLOW_LOOPS) {
    const uint32_t bits = c[AM_CTL_OVERFLOW];
    const SlotWalk walk = m.slotWalk[slot];
    if (m.lastRegionLists || (walk.lists && !walk.conservative))
      m.conservativeRegions = true;  // the next frames spare the device more
    if (bits & AM_OVERFLOW_CUT_NORMALS) m.conservativeNormals = true;
    // That frame drew nothing; the next record redoes it with single-block lists (and the normals
    // one vertex a dispatch), as polygonize() redoes its frame. Cut again so: the CPU's.
    if (cutFrameRedoable(bits, walk)) {
      ++m.cutFramesRedone;
      return Status::success();
    }
    m.cutLoops = true;  // redoing it would cut them again
    m.cutLoopsBits = bits;
    return Error{cutLoopsError(m.cutLoopsBits)};
  }
  // That frame drew nothing; grow to what it needed (counts past a block overflow are
  // partial, so those buffers double too) for the record that redoes it.
  bool blocksShort = (c[AM_CTL_OVERFLOW] & AM_OVERFLOW_BLOCKS) != 0;
  uint32_t vw = c[AM_CTL_VERTICES] + c[AM_CTL_VERTICES] / 4, tw = c[AM_CTL_TRIANGLES] + c[AM_CTL_TRIANGLES] / 4;
  if (blocksShort) {
    vw = std::max(vw, 2 * m.vertexCapacity);
    tw = std::max(tw, 2 * m.triangleCapacity);
  }
  return m.ensureCapacities(c[AM_CTL_ACTIVE] + c[AM_CTL_ACTIVE] / 4, vw, tw);
}

Result<bool> GpuPolygonizer::recordFitted(uint64_t frameSerial) {
  const uint32_t slot = uint32_t(frameSerial % kFramesInFlight);
  if (impl_->slotSerial[slot] != frameSerial) return Error{"GPU polygoniser: the counters of that record are gone"};
  if (Status g = absorbCounters(slot); !g) return Error{g.error()};
  return !stats_.overflowed;
}

Status GpuPolygonizer::record(VkCommandBuffer cmd, uint64_t frameSerial, const GpuField& field,
                              const GpuPolygonizeSettings& s, const GpuPreparedFrame* prepared) {
  Impl& m = *impl_;
  const uint32_t slot = uint32_t(frameSerial % kFramesInFlight);
  // The counters of the frame that last used this slot (complete, by the caller's contract).
  if (Status g = absorbCounters(slot); !g) return g;
  if (m.cutLoops) {
    m.cutLoops = false;
    return Error{cutLoopsError(m.cutLoopsBits)};
  }
  // First frames: size the buffers for the grid as polygonize() does.
  const FramePrep* prep = m.usable(prepared, field, s);
  if (Result<Grid> g = prep ? Result<Grid>(prep->g) : makeGrid(field, s); g) {
    uint32_t blocks = firstBlockCapacity(g->blocks());
    if (blocks > m.blockCapacity) {
      Status e = m.ensureCapacities(blocks, blocks * 192, blocks * 384);
      if (!e) return e;
    }
  }
  m.slotSerial[slot] = frameSerial;
  const bool conservative = m.conservativeRegions;  // (what a prepared frame's lists must match, Impl::usable)
  Status st = m.recordFrame(cmd, slot, field, s, stats_, false, prepared);
  m.slotWalk[slot] = SlotWalk{stats_.regionLists, conservative, m.normalsPerVertex};
  return st;
}

uint64_t GpuPolygonizer::cutFramesRedone() const { return impl_->cutFramesRedone; }

namespace {
// Whether a and b override the grid alike (both not, or with the same grid).
bool sameGridOverride(const GpuPolygonizeSettings& a, const GpuPolygonizeSettings& b) {
  if (a.grid.has_value() != b.grid.has_value()) return false;
  if (!a.grid) return true;
  const PolygonizeGrid &x = *a.grid, &y = *b.grid;
  return x.origin == y.origin && x.cellSize == y.cellSize && x.cells[0] == y.cells[0] && x.cells[1] == y.cells[1] &&
         x.cells[2] == y.cells[2];
}
}  // namespace

Result<PolygonizeGrid> GpuPolygonizer::grid(const GpuField& field, const GpuPolygonizeSettings& s) {
  if (s.resolution < 2 || s.resolution > 512)
    return Error{"GPU polygoniser: resolution " + std::to_string(s.resolution) + " is out of range (2..512)"};
  bool empty = false;
  Result<Grid> g = makeGrid(field, s, &empty);
  if (!g) return Error{g.error()};
  PolygonizeGrid r;
  r.origin = g->origin;
  r.cellSize = g->h;
  for (int a = 0; a < 3; ++a) r.cells[a] = int(g->n[a]);
  r.empty = empty;
  return r;
}

const FramePrep* GpuPolygonizer::Impl::usable(const GpuPreparedFrame* prepared, const GpuField& field,
                                              const GpuPolygonizeSettings& s) const {
  if (!prepared) return nullptr;
  const GpuPreparedFrame::Data& d = *prepared->d_;
  const GpuField& f = d.field;
  const GpuPolygonizeSettings& p = d.settings;
  // What the grid, the packing and the lists depend on (the morph's weights and the passes' other
  // settings are read at the record).
  const bool same = f.a == field.a && f.b == field.b && f.colors == field.colors && p.colors == s.colors &&
                    p.colorRegionLists == s.colorRegionLists &&
                    f.method == field.method && p.resolution == s.resolution &&
                    p.marginCells == s.marginCells && p.regionPrograms == s.regionPrograms &&
                    p.loopBudgetCheck == s.loopBudgetCheck && p.bounds.has_value() == s.bounds.has_value() &&
                    (!s.bounds || (p.bounds->min == s.bounds->min && p.bounds->max == s.bounds->max)) &&
                    sameGridOverride(p, s);
  if (!same || d.loopLimit != loopLimit(ctx.properties())) return nullptr;
  if (d.prep.lists && d.prep.conservative != conservativeRegions) return nullptr;
  return &d.prep;
}

Result<std::shared_ptr<const GpuPreparedFrame>> GpuPolygonizer::prepare(const GpuField& field,
                                                                        const GpuPolygonizeSettings& s,
                                                                        uint64_t loopLimit,
                                                                        const GpuPreparedFrame* previous,
                                                                        bool conservativeRegions) {
  if (std::string why = unsupported(field); !why.empty()) return Error{"GPU polygoniser: " + why};
  const auto t0 = std::chrono::steady_clock::now();
  Result<FramePrep> prep = prepareFrame(field, s, loopLimit, conservativeRegions);
  if (!prep) return Error{prep.error()};
  auto d = std::make_unique<GpuPreparedFrame::Data>();
  d->field = field;
  d->settings = s;
  d->loopLimit = loopLimit;
  d->prep = std::move(*prep);
  d->id = ++gPreparedIds;
  if (previous && s.reuseToleranceCells >= 0.0f) {
    d->blockBounds = blockChangeBounds(field, d->prep, previous->d_->field, previous->d_->prep);
    if (!d->blockBounds.empty()) d->previousId = previous->d_->id;
  }
  d->milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return std::shared_ptr<const GpuPreparedFrame>(new GpuPreparedFrame(std::move(d)));
}

uint64_t GpuPolygonizer::preparesInRecord() const { return impl_->preparesInRecord; }
bool GpuPolygonizer::conservativeRegions() const { return impl_->conservativeRegions; }

Status GpuPolygonizer::record(VkCommandBuffer cmd, uint64_t frameSerial, const GpuField& field,
                              const GpuPolygonizeSettings& s) {
  return record(cmd, frameSerial, field, s, nullptr);
}

Result<GpuPolygonizeStats> GpuPolygonizer::polygonize(const GpuField& field, const GpuPolygonizeSettings& s) {
  return polygonize(field, s, nullptr);
}

GeneratedMeshDraw GpuPolygonizer::generatedMesh(const glm::vec4& color) const {
  GeneratedMeshDraw d;
  d.positions = impl_->positions.buffer;
  d.normals = impl_->normals.buffer;
  d.indices = impl_->indices.buffer;
  d.indirect = impl_->control.buffer;
  d.indirectOffset = AM_CTL_DRAW * 4;
  d.color = color;
  return d;
}

Result<GpuPolygonizeStats> GpuPolygonizer::polygonize(const GpuField& field, const GpuPolygonizeSettings& s,
                                                      const GpuPreparedFrame* prepared) {
  Impl& m = *impl_;
  if (std::string why = unsupported(field); !why.empty()) return Error{"GPU polygoniser: " + why};
  // Initial capacities for this grid (or the caller's, e.g. tiny ones in tests).
  {
    const FramePrep* prep = m.usable(prepared, field, s);
    Result<Grid> g = prep ? Result<Grid>(prep->g) : makeGrid(field, s);
    if (!g) return Error{g.error()};
    uint32_t nb = g->blocks();
    uint32_t blocks = s.initialBlockCapacity ? s.initialBlockCapacity : firstBlockCapacity(nb);
    uint32_t verts = s.initialVertexCapacity ? s.initialVertexCapacity : blocks * 192;
    uint32_t tris = s.initialTriangleCapacity ? s.initialTriangleCapacity : blocks * 384;
    if (s.initialBlockCapacity || s.initialVertexCapacity || s.initialTriangleCapacity) {
      // Start from exactly the requested sizes: drop larger buffers first.
      m.ctx.waitIdle();
      for (Buffer* b : {&m.active, &m.corners, &m.edges, &m.counts, &m.offsets, &m.positions, &m.normals, &m.indices})
        destroyBuffer(m.ctx.device(), *b);
      m.blockCapacity = m.vertexCapacity = m.triangleCapacity = 0;
    }
    Status e = m.ensureCapacities(blocks, verts, tris);
    if (!e) return Error{e.error()};
  }
  const uint32_t slot = kFramesInFlight;  // the synchronous path's own read-back slot
  GpuPolygonizeStats stats;
  auto t0 = std::chrono::steady_clock::now();
  for (int attempt = 0; attempt < 16; ++attempt) {
    VkDevice dev = m.ctx.device();
    AM_VK_TRY(vkResetCommandBuffer(m.cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    AM_VK_TRY(vkBeginCommandBuffer(m.cmd, &bi), "vkBeginCommandBuffer");
    Status rec = m.recordFrame(m.cmd, slot, field, s, stats, true, prepared);
    AM_VK_TRY(vkEndCommandBuffer(m.cmd), "vkEndCommandBuffer");
    if (!rec) return Error{rec.error()};
    if (attempt == 0) t0 = std::chrono::steady_clock::now();
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &m.cmd;
    AM_VK_TRY(vkResetFences(dev, 1, &m.fence), "vkResetFences");
    AM_VK_TRY(vkQueueSubmit(m.ctx.queue(), 1, &si, m.fence), "GPU polygoniser: vkQueueSubmit");
    AM_VK_TRY(vkWaitForFences(dev, 1, &m.fence, VK_TRUE, UINT64_MAX), "GPU polygoniser: waiting for the GPU");
    const auto* c = static_cast<const uint32_t*>(m.readback.mapped) + slot * AM_CTL_READBACK_UINTS;
    stats.blocksActive = c[AM_CTL_ACTIVE];
    stats.vertices = c[AM_CTL_VERTICES];
    stats.triangles = c[AM_CTL_TRIANGLES];
    stats.blocksReused = c[AM_CTL_REUSED];
    uint32_t overflow = c[AM_CTL_OVERFLOW];
    if (overflow & AM_OVERFLOW_LOOPS) {
      const bool normalsRedo = (overflow & AM_OVERFLOW_CUT_NORMALS) && stats.regionLists && !m.normalsPerVertex;
      if (!m.lastRegionLists && !normalsRedo) return Error{cutLoopsError(overflow)};
      if (normalsRedo) m.conservativeNormals = true;  // redo it with the normals one vertex at a time
      if ((overflow & (AM_OVERFLOW_CUT_COARSE | AM_OVERFLOW_CUT_CELLS)) != 0 || !normalsRedo)
        m.conservativeRegions = true;  // redo it with the smallest regions
      continue;
    }
    if (overflow == 0) {
      uint64_t ticks[kTimestamps] = {};
      if (m.timestamps && vkGetQueryPoolResults(dev, m.timestamps, 0, kTimestamps, sizeof ticks, ticks, sizeof(uint64_t),
                                                VK_QUERY_RESULT_64_BIT) == VK_SUCCESS) {
        const double period = m.ctx.properties().limits.timestampPeriod * 1e-6;
        for (uint32_t k = 0; k + 1 < kTimestamps; ++k) stats.passMs[k] = double(ticks[k + 1] - ticks[k]) * period;
      }
      stats.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      stats_ = stats;
      m.haveMesh = true;
      return stats;
    }
    ++stats.regrows;
    Status g = Status::success();
    if (overflow & AM_OVERFLOW_BLOCKS) {
      // Counts beyond the processed blocks are unknown: grow those buffers too.
      g = m.ensureCapacities(stats.blocksActive, std::max(m.vertexCapacity * 2, stats.vertices),
                             std::max(m.triangleCapacity * 2, stats.triangles));
    } else {
      g = m.ensureCapacities(0, stats.vertices, stats.triangles);
    }
    if (!g) return Error{g.error()};
  }
  return Error{"GPU polygoniser: the mesh still overflowed its buffers after 16 attempts"};
}

Result<TriangleMesh> GpuPolygonizer::readBack() {
  Impl& m = *impl_;
  if (!m.haveMesh) return Error{"GPU polygoniser: nothing polygonised yet"};
  const VkDeviceSize vbytes = VkDeviceSize(stats_.vertices) * kVertexStride, ibytes = VkDeviceSize(stats_.triangles) * 12;
  TriangleMesh mesh;
  if (stats_.triangles == 0) return mesh;
  Result<Buffer> host = createHostBuffer(m.ctx, 2 * vbytes + ibytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  if (!host) return Error{"GPU polygoniser read-back: " + host.error()};
  Status s = m.ctx.submitImmediate([&](VkCommandBuffer cmd) {
    VkBufferCopy p{0, 0, vbytes}, n{0, vbytes, vbytes}, i{0, 2 * vbytes, ibytes};
    vkCmdCopyBuffer(cmd, m.positions.buffer, host->buffer, 1, &p);
    vkCmdCopyBuffer(cmd, m.normals.buffer, host->buffer, 1, &n);
    vkCmdCopyBuffer(cmd, m.indices.buffer, host->buffer, 1, &i);
    barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_ACCESS_HOST_READ_BIT);
  });
  if (!s) {
    destroyBuffer(m.ctx.device(), *host);
    return Error{"GPU polygoniser read-back: " + s.error()};
  }
  const auto* bytes = static_cast<const uint8_t*>(host->mapped);
  mesh.positions.resize(stats_.vertices);
  mesh.normals.resize(stats_.vertices);
  mesh.indices.resize(size_t(stats_.triangles) * 3);
  for (size_t v = 0; v < stats_.vertices; ++v) {  // vec4 per vertex on the device
    std::memcpy(&mesh.positions[v], bytes + v * kVertexStride, 12);
    std::memcpy(&mesh.normals[v], bytes + vbytes + v * kVertexStride, 12);
  }
  if (stats_.colors) {  // the colour pass's RGBA8 in the normals' w (poly_color_main.glsl), linear
    mesh.colors.resize(stats_.vertices);
    for (size_t v = 0; v < stats_.vertices; ++v) {
      uint32_t bits = 0;
      std::memcpy(&bits, bytes + vbytes + v * kVertexStride + 12, 4);
      mesh.colors[v] = glm::vec4(float(bits & 0xffu), float((bits >> 8) & 0xffu), float((bits >> 16) & 0xffu), 255.0f) / 255.0f;
    }
  }
  std::memcpy(mesh.indices.data(), bytes + 2 * vbytes, ibytes);
  destroyBuffer(m.ctx.device(), *host);
  return mesh;
}

}  // namespace animorph::gpu
