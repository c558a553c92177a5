// Benchmark of temporal coherence on the GPU polygoniser (GpuPolygonizeSettings::reuseToleranceCells,
// frames prepared against the previous one): consecutive frames (1/24 s apart) of the demo's dragon
// flapping its wings with the body held and of the dinosaur moving its tail, at 128^3 on one grid
// (the union of the frames' bounds), polygonised as full sweeps (the baseline, same run), with exact
// reuse and within 0.1 cell. Each mode's frames once, in order (no median: a frame takes seconds on
// lavapipe); wall time per frame including the read-back, one polygonisation at a time (latency);
// the preparation (bounds, packing, lists, change bounds) is on the host and timed apart.
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_hold_tracks.h"
#include "core/blobtree/compile.h"
#include "core/project/animorphosis_project.h"
#include "demo/animorphosis_demo.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/vulkan/context.h"

namespace {

using namespace animorph;
using animorph::bench::Row;
namespace g = animorph::gpu;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct ModeRun {
  double ms = 0.0, prepareMs = 0.0;
  uint64_t reused = 0, active = 0;
  int withBounds = 0, coherent = 0;  // frames prepared with change bounds; frames recorded with them
  std::vector<TriangleMesh> meshes;
  std::string error;
};

// The frames in order; tolerance < 0: full sweeps (no prepared frames).
ModeRun runMode(g::GpuPolygonizer& poly, uint64_t limit, const std::vector<FieldProgram>& programs,
                g::GpuPolygonizeSettings s, float tolerance) {
  ModeRun m;
  s.reuseToleranceCells = tolerance;
  std::shared_ptr<const g::GpuPreparedFrame> previous;
  for (const FieldProgram& p : programs) {
    const g::GpuField f = g::GpuField::single(p);
    std::shared_ptr<const g::GpuPreparedFrame> prepared;
    if (tolerance >= 0.0f) {
      const auto t0 = Clock::now();
      auto r = g::GpuPolygonizer::prepare(f, s, limit, previous.get(), poly.conservativeRegions());
      m.prepareMs += msSince(t0);
      if (!r) {
        m.error = r.error();
        return m;
      }
      prepared = *r;
      m.withBounds += prepared->hasChangeBounds() ? 1 : 0;
    }
    const auto t0 = Clock::now();
    auto st = poly.polygonize(f, s, prepared.get());
    auto mesh = st ? poly.readBack() : Result<TriangleMesh>(Error{st.error()});
    m.ms += msSince(t0);
    if (!mesh) {
      m.error = mesh.error();
      return m;
    }
    m.reused += st->blocksReused;
    m.coherent += st->coherent ? 1 : 0;
    m.active += st->blocksActive;
    m.meshes.push_back(std::move(*mesh));
    previous = prepared;
  }
  return m;
}

void caseRows(g::GpuPolygonizer& poly, uint64_t limit, const std::string& what,
              const std::function<FieldProgram(int)>& frame, int frames, int res, std::vector<Row>& rows) {
  std::vector<FieldProgram> programs;
  Bounds box;
  for (int f = 0; f < frames; ++f) {
    programs.push_back(frame(f));
    box.add(programs.back().bounds());
  }
  g::GpuPolygonizeSettings s;
  s.resolution = res;
  s.bounds = box;
  const std::string head = std::to_string(frames) + " consecutive frames " + what + " at " + std::to_string(res) + "^3, GPU";
  const ModeRun full = runMode(poly, limit, programs, s, -1.0f);
  const ModeRun exact = runMode(poly, limit, programs, s, 0.0f);
  const ModeRun tol = runMode(poly, limit, programs, s, 0.1f);
  for (const ModeRun* m : {&full, &exact, &tol})
    if (!m->error.empty()) {
      rows.push_back({head + " failed", 0, "", "", m->error});
      return;
    }
  bool same = true, sameTriangles = true;
  double deviation = 0.0;
  for (int f = 0; f < frames; ++f) {
    const TriangleMesh &a = full.meshes[size_t(f)], &b = exact.meshes[size_t(f)], &c = tol.meshes[size_t(f)];
    same &= a.positions == b.positions && a.indices == b.indices;
    sameTriangles &= a.indices == c.indices && a.positions.size() == c.positions.size();
    for (size_t i = 0; i < a.positions.size() && i < c.positions.size(); ++i)
      deviation = std::max(deviation, double(glm::length(a.positions[i] - c.positions[i])));
  }
  auto st = poly.lastStats();
  const double cell = st.cellSize > 0.0f ? double(st.cellSize) : 1.0;
  const std::string how = "wall per frame incl. read-back, one at a time, each frame once";
  auto blocks = [](const ModeRun& m) {
    return std::to_string(m.reused) + " of " + std::to_string(m.active) + " active blocks reused (" +
           std::to_string(m.withBounds) + " frames had change bounds, " + std::to_string(m.coherent) +
           " were recorded with them)";
  };
  char prep[120];
  rows.push_back({head + ", full sweeps (baseline)", full.ms / frames, "ms/frame", "", how});
  std::snprintf(prep, sizeof prep, "; host preparation %.1f ms/frame apart (the editor's compile thread)",
                exact.prepareMs / frames);
  rows.push_back({head + ", exact reuse", exact.ms / frames, "ms/frame", "",
                  blocks(exact) + "; meshes " + (same ? "identical" : "DIFFER") + "; " + how + prep});
  char dev[96];
  std::snprintf(dev, sizeof dev, "largest vertex deviation from the full sweeps %.4f cell", deviation / cell);
  std::snprintf(prep, sizeof prep, "; host preparation %.1f ms/frame apart", tol.prepareMs / frames);
  rows.push_back({head + ", reuse within 0.1 cell", tol.ms / frames, "ms/frame", "",
                  blocks(tol) + "; triangles " + (sameTriangles ? "identical" : "DIFFER") + ", " + dev + "; " + how + prep});
}

std::vector<Row> runGpuCoherence(const animorph::bench::Options& opt) {
  bool wanted = opt.gpu;
  for (const auto& f : opt.filters) wanted |= f.find("gpu") != std::string::npos;
  if (!wanted) return {{"skipped", 0, "", "", "run `bench gpu-coherence` or pass --gpu"}};
  auto ctx = g::Context::create(g::ContextSettings{});
  if (!ctx) return {{"skipped", 0, "", "", "no Vulkan device: " + ctx.error()}};
  auto poly = g::GpuPolygonizer::create(**ctx);
  if (!poly) return {{"skipped", 0, "", "", poly.error()}};
  auto project = makeAnimorphosisDemoProject();
  if (!project) return {{"skipped", 0, "", "", project.error()}};
  std::vector<Row> rows;
  rows.push_back({"device", 0, "", "", (*ctx)->deviceName()});
  const uint64_t limit = g::GpuPolygonizer::loopLimit((*ctx)->properties());
  const int frames = opt.quick ? 2 : 4, res = 128;
  const BlobTree wingsOnly = benchHoldAllBut(project->actors[1].blobTree, "wing", 0.0);
  const BlobTree tailOnly = benchHoldAllBut(project->actors[0].blobTree, "tail", 0.0);
  caseRows(**poly, limit, "of the dragon, wings flapping, body held",
           [&](int f) { return compileFieldProgram(wingsOnly, 0.5 + f / 24.0); }, frames, res, rows);
  caseRows(**poly, limit, "of the dinosaur, tail moving, body held",
           [&](int f) { return compileFieldProgram(tailOnly, 0.5 + f / 24.0); }, frames, res, rows);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("gpu-coherence", "Temporal coherence on the GPU polygoniser: the demo's dragon and dinosaur, one part moving",
               runGpuCoherence);
