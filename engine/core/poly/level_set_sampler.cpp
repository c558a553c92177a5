#include "core/poly/level_set_sampler.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/field/surface_color.h"
#include "core/poly/solid_noise.h"

namespace animorph {

namespace {

constexpr int kBlock = 8;  // voxels per block side

struct Scratch {
  FieldEvaluator evaluator;
  ActiveProgram active;
  std::vector<uint32_t> reaching;
  std::vector<float> x, y, z, f, gx, gy, gz;
};

struct BlockBand {
  std::vector<glm::ivec3> index;
  std::vector<float> distance;
};

// Signed distance to the box [lo, hi] (negative inside).
float boxDistance(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 q = glm::abs(p - 0.5f * (lo + hi)) - 0.5f * (hi - lo);
  return glm::length(glm::max(q, glm::vec3(0.0f))) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
}

// The surface colour at the band's voxels next to the surface (LevelSetSettings::colors).
void colorBand(const FieldProgram& program, int threads, LevelSetVoxels& out) {
  const float near = kColorBandVoxels * out.voxelSize;
  std::vector<glm::vec3> points;
  for (size_t v = 0; v < out.index.size(); ++v) {
    if (std::abs(out.distance[v]) >= near) continue;
    out.colorVoxel.push_back(uint32_t(v));
    points.push_back(out.origin + out.voxelSize * glm::vec3(out.index[v]));
  }
  std::vector<glm::vec4> rgba(points.size());
  SurfaceColorEvaluator().evaluate(program, points.data(), points.size(), rgba.data(), threads);
  out.color.resize(rgba.size());
  for (size_t i = 0; i < rgba.size(); ++i) out.color[i] = glm::vec3(rgba[i]);
}

}  // namespace

Result<LevelSetVoxels> sampleLevelSet(const FieldProgram& program, const LevelSetSettings& s) {
  if (!(s.halfWidth >= 1.0f && s.halfWidth <= 16.0f))
    return Error{"level set: half-width " + std::to_string(s.halfWidth) + " voxels is outside 1..16"};
  auto grid = polygonizeGrid(program, s.grid);
  if (!grid) return Error{"level set: " + grid.error()};
  LevelSetVoxels out;
  if (grid->empty) return out;  // inside nowhere: an empty band (all outside)
  const float h = grid->cellSize;
  out.origin = grid->origin;
  out.voxelSize = h;
  out.background = s.halfWidth * h;
  for (int a = 0; a < 3; ++a) out.cells[a] = grid->cells[a];
  const glm::vec3 boxLo = grid->origin;
  const glm::vec3 boxHi = grid->origin + h * glm::vec3(float(grid->cells[0]), float(grid->cells[1]), float(grid->cells[2]));
  const float band = out.background;
  const float noiseReach = std::abs(s.noiseAmplitude);

  // Voxels lo..hi per axis: the grid and the band around it.
  const int pad = int(std::ceil(s.halfWidth)) + 1;
  int lo[3], nb[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = -pad;
    nb[a] = (grid->cells[a] + 2 * pad + 1 + kBlock - 1) / kBlock;
  }
  const size_t blocks = size_t(nb[0]) * size_t(nb[1]) * size_t(nb[2]);
  std::vector<BlockBand> bands(blocks);
  std::atomic<size_t> points{0};
  std::atomic<bool> cancelled{false};
  const float margin = 1e-3f * program.threshold + 1e-7f;  // float rounding of the interval (as the polygoniser's)
  auto voxelPos = [&](int i, int j, int k) { return grid->origin + h * glm::vec3(float(i), float(j), float(k)); };

  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::task_arena arena(s.grid.threads > 0 ? s.grid.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), blocks, [&](size_t bi) {
      if (cancelled.load(std::memory_order_relaxed)) return;
      if (s.grid.cancel && s.grid.cancel->load(std::memory_order_relaxed)) {
        cancelled = true;
        return;
      }
      Scratch& sc = scratch.local();
      const int b[3] = {int(bi % size_t(nb[0])), int((bi / size_t(nb[0])) % size_t(nb[1])),
                        int(bi / (size_t(nb[0]) * size_t(nb[1])))};
      const glm::ivec3 v0(lo[0] + b[0] * kBlock, lo[1] + b[1] * kBlock, lo[2] + b[2] * kBlock);
      // The block's voxels and everything within the band (and the noise's reach) of them.
      const float reach = band + noiseReach;
      Bounds region;
      region.add(voxelPos(v0.x, v0.y, v0.z) - glm::vec3(reach));
      region.add(voxelPos(v0.x + kBlock - 1, v0.y + kBlock - 1, v0.z + kBlock - 1) + glm::vec3(reach));
      program.primitivesReaching(region, sc.reaching);
      program.specialise(sc.reaching, sc.active);
      const Interval iv = program.interval(sc.active, region.center(), 0.5f * region.diagonal());
      if (iv.hi < -margin) return;  // outside, farther than the band from the surface
      const bool inBox = glm::all(glm::greaterThanEqual(region.min, boxLo)) && glm::all(glm::lessThanEqual(region.max, boxHi));
      if (iv.lo > margin && inBox) return;  // inside, farther than the band (the flood fill marks it)

      constexpr int n = kBlock * kBlock * kBlock;
      for (auto* v : {&sc.x, &sc.y, &sc.z, &sc.f, &sc.gx, &sc.gy, &sc.gz}) v->resize(n);
      for (int k = 0, q = 0; k < kBlock; ++k)
        for (int j = 0; j < kBlock; ++j)
          for (int i = 0; i < kBlock; ++i, ++q) {
            const glm::vec3 p = voxelPos(v0.x + i, v0.y + j, v0.z + k);
            sc.x[q] = p.x;
            sc.y[q] = p.y;
            sc.z[q] = p.z;
          }
      sc.evaluator.evaluate(program, sc.active, sc.x.data(), sc.y.data(), sc.z.data(), n, sc.f.data(), sc.gx.data(),
                            sc.gy.data(), sc.gz.data());
      points += size_t(n);
      BlockBand& outBlock = bands[bi];
      for (int k = 0, q = 0; k < kBlock; ++k)
        for (int j = 0; j < kBlock; ++j)
          for (int i = 0; i < kBlock; ++i, ++q) {
            const glm::vec3 p(sc.x[q], sc.y[q], sc.z[q]);
            const float g = std::sqrt(sc.gx[q] * sc.gx[q] + sc.gy[q] * sc.gy[q] + sc.gz[q] * sc.gz[q]);
            // First order: the distance to the zero of the field's tangent plane. A flat field
            // (g ~ 0: deep inside a blob, or far outside) is beyond the band on its side.
            float d = g > 1e-20f ? -sc.f[q] / g : (sc.f[q] >= 0.0f ? -band : band);
            if (!std::isfinite(d)) d = sc.f[q] >= 0.0f ? -band : band;
            if (noiseReach > 0.0f) d -= s.noiseAmplitude * solidNoise(s.noiseFrequency * p);
            d = std::max(d, boxDistance(p, boxLo, boxHi));  // cut by the grid, as the polygoniser's surface
            if (std::abs(d) >= band) continue;
            outBlock.index.emplace_back(v0.x + i, v0.y + j, v0.z + k);
            outBlock.distance.push_back(d);
          }
    });
  });
  out.pointsEvaluated = points;
  out.cancelled = cancelled;
  if (out.cancelled) return out;
  size_t total = 0;
  for (const BlockBand& bb : bands) total += bb.index.size();
  out.index.reserve(total);
  out.distance.reserve(total);
  for (BlockBand& bb : bands) {
    out.index.insert(out.index.end(), bb.index.begin(), bb.index.end());
    out.distance.insert(out.distance.end(), bb.distance.begin(), bb.distance.end());
  }
  if (s.colors) colorBand(s.colorProgram ? *s.colorProgram : program, s.grid.threads, out);
  return out;
}

}  // namespace animorph
