// Benchmark of the GPU polygoniser against the CPU one, side by side in one run:
// the interpolation morph of two stand-ins (seeded chains of 20 convolution
// segments each, 40 in all, one walk with different joints and radii) at w = 0.5. The CPU polygonises the same field as
// one program (B's weights scaled by w, A's by 1 - w: the convolution field is
// linear in its weights), so both sides make the same mesh.
#include <algorithm>
#include <optional>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <chrono>
#include <random>
#include <thread>

#include <sys/resource.h>

#include "core/blobtree/compile.h"
#include "app/cli/bench/bench.h"
#include "core/animorphosis/compile_generic.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/project/animorphosis_project.h"
#include "demo/animorphosis_demo.h"
#include "demo/blob_creature.h"
#include "core/poly/polygonizer.h"
#include "app/cli/bench/bench_demo_morph.h"
#include "core/scene/morph_runtime.h"
#include "gpu/vulkan/context.h"
#include "gpu/polygonizer/gpu_field_program.h"
#include "gpu/polygonizer/gpu_polygonizer.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

constexpr unsigned kWalkSeed = 2024u;

// A stand-in: a seeded random walk of n convolution segments inside the unit
// cube; detailSeed jitters the joints and picks the radii, so two stand-ins of
// one walk overlap like a character and its morph target.
BlobNode chain(int n, unsigned walkSeed, unsigned detailSeed, int& id) {
  std::mt19937 walk(walkSeed), detail(detailSeed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  BlobNode blend = makeBlobNode(NodeType::Blend, id++, "stand-in");
  glm::vec3 p(0.0f, 0.0f, -0.3f);
  glm::vec3 dir(0.0f, 0.0f, 1.0f);
  std::vector<glm::vec3> joints{p};
  for (int i = 0; i < n; ++i) {
    dir = glm::normalize(dir + 0.8f * glm::vec3(u(walk), u(walk), u(walk)));
    p = glm::clamp(p + 0.09f * dir, glm::vec3(-0.36f), glm::vec3(0.36f));
    joints.push_back(p);
  }
  for (glm::vec3& j : joints) j += 0.03f * glm::vec3(u(detail), u(detail), u(detail));
  for (int i = 0; i < n; ++i) {
    BlobNode s = makeBlobNode(NodeType::ConvSegment, id++);
    s.vec3Param("a") = Vec3Track(joints[size_t(i)]);
    s.vec3Param("b") = Vec3Track(joints[size_t(i + 1)]);
    s.floatParam("radius") = FloatTrack(0.05f + 0.02f * u(detail));
    s.floatParam("sharpness") = FloatTrack(12.0f);
    blend.children.push_back(s);
  }
  return blend;
}

FieldProgram standIn(unsigned detailSeed) {
  int id = 1;
  BlobTree tree;
  tree.threshold = FloatTrack(1.0f);
  tree.root = chain(20, kWalkSeed, detailSeed, id);
  return compileFieldProgram(tree, 0.0);
}

// One program whose field is (1 - w) fA + w fB for two convolution-only programs of equal threshold.
FieldProgram interpolatedProgram(unsigned seedA, unsigned seedB, float w) {
  int id = 1;
  BlobTree tree;
  tree.threshold = FloatTrack(1.0f);
  tree.root = makeBlobNode(NodeType::Blend, id++, "morph");
  tree.root.children.push_back(chain(20, kWalkSeed, seedA, id));
  tree.root.children.push_back(chain(20, kWalkSeed, seedB, id));
  FieldProgram p = compileFieldProgram(tree, 0.0);
  for (size_t i = 0; i < p.convolution.size(); ++i) p.convolution.weight[i] *= i < 20 ? 1.0f - w : w;
  return p;
}

std::string loadAverage() {
  std::string load = "?";
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    char buf[64] = {};
    if (std::fgets(buf, sizeof buf, f)) load = std::string(buf).substr(0, std::string(buf).find(' '));
    std::fclose(f);
  }
  return load;
}

// CPU time (user + system, all threads of the process) that fn takes, in ms.
template <class Fn>
double processCpuMs(Fn&& fn) {
  auto now = [] {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return 1e3 * double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-3 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  double a = now();
  fn();
  return now() - a;
}

Bounds unitCube() {
  Bounds b;
  b.add(glm::vec3(-0.5f));
  b.add(glm::vec3(0.5f));
  return b;
}

namespace g = animorph::gpu;

// Threads the CPU baseline runs on: as many as the device uses. lavapipe runs its shaders on
// LP_NUM_THREADS worker threads, one per core by default; beside a real GPU, every core too.
int baselineThreads() {
  if (const char* lp = std::getenv("LP_NUM_THREADS")) {
    const int n = std::atoi(lp);
    if (n > 0) return n;
  }
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

// The grid sizes to measure: 64 (quick) or 64, 128, 256; ANIMORPH_BENCH_GPU_RES (e.g. "128")
// picks some while tuning.
std::vector<int> gpuBenchSizes(const animorph::bench::Options& opt) {
  std::vector<int> sizes = opt.quick ? std::vector<int>{64} : std::vector<int>{64, 128, 256};
  if (const char* only = std::getenv("ANIMORPH_BENCH_GPU_RES")) {  // e.g. "128": one size while tuning
    sizes.clear();
    for (const char* c = only; *c;) {
      char* end = nullptr;
      long v = std::strtol(c, &end, 10);
      if (end == c) break;
      if (v == 64 || v == 128 || v == 256) sizes.push_back(int(v));
      c = *end ? end + 1 : end;
    }
  }
  return sizes;
}

struct GpuTimes {
  g::GpuPolygonizeStats culled, dense;  // culled: each pass's median over the culled runs
  double ms = 0.0, cpuMs = 0.0, denseMs = 0.0;  // median wall, mean process CPU, dense median wall
  double readBackMs = 0.0;                      // median of the read-back alone (inside ms)
  std::string error;
};

GpuTimes timeGpu(g::GpuPolygonizer& poly, const g::GpuField& field, int res, int reps, bool withDense) {
  GpuTimes t;
  g::GpuPolygonizeSettings gs;
  gs.resolution = res;
  gs.bounds = unitCube();
  std::vector<std::array<double, 6>> culledPasses;  // per run, for medians per pass
  std::vector<double> readBackMs;
  auto runGpu = [&](bool cull, g::GpuPolygonizeStats& out) {
    gs.culling = cull;
    auto r = poly.polygonize(field, gs);
    if (r) out = *r;
    else t.error = r.error();
    // The mesh reaches host memory inside the timing, as the CPU's does.
    if (r) {
      const auto rb = std::chrono::steady_clock::now();
      auto mesh = poly.readBack();
      if (!mesh) t.error = mesh.error();
      if (cull) readBackMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - rb).count());
    }
    if (r && cull) culledPasses.push_back({r->passMs[0], r->passMs[1], r->passMs[2], r->passMs[3], r->passMs[4], r->passMs[5]});
  };
  // medianMs warms up first (pipelines compile lazily on lavapipe, buffers grow).
  t.ms = animorph::bench::medianMs(reps, [&] { runGpu(true, t.culled); });
  // Process CPU time of one culled run (lavapipe's worker threads included): on a
  // loaded machine the wall time includes waiting for a core, this does not.
  t.cpuMs = processCpuMs([&] {
              for (int k = 0; k < reps; ++k) runGpu(true, t.culled);
            }) / reps;
  // Median of each pass over the culled runs (timestamps of one run are noisy on a loaded machine).
  for (int k = 0; k < 6; ++k) {
    std::vector<double> v;
    for (const auto& p : culledPasses) v.push_back(p[size_t(k)]);
    std::sort(v.begin(), v.end());
    if (!v.empty()) t.culled.passMs[k] = v[v.size() / 2];
  }
  std::sort(readBackMs.begin(), readBackMs.end());
  if (!readBackMs.empty()) t.readBackMs = readBackMs[readBackMs.size() / 2];
  t.denseMs = withDense ? animorph::bench::medianMs(res >= 256 ? 1 : 3, [&] { runGpu(false, t.dense); }) : 0.0;
  return t;
}

struct CpuTimes {
  PolygonizeResult culled, dense;
  double ms = 0.0, cpuMs = 0.0, denseMs = 0.0;
};

CpuTimes timeCpu(const FieldProgram& merged, int res, int reps, bool withDense, int threads) {
  CpuTimes t;
  PolygonizeSettings cs;
  cs.resolution = res;
  cs.bounds = unitCube();
  cs.threads = threads;
  t.ms = animorph::bench::medianMs(reps, [&] {
    cs.culling = true;
    if (auto r = polygonize(merged, cs)) t.culled = std::move(*r);
  });
  t.cpuMs = processCpuMs([&] {
              cs.culling = true;
              for (int k = 0; k < reps; ++k)
                if (auto r = polygonize(merged, cs)) t.culled = std::move(*r);
            }) / reps;
  t.denseMs = !withDense ? 0.0 : animorph::bench::medianMs(res >= 256 ? 1 : 3, [&] {
    cs.culling = false;
    if (auto r = polygonize(merged, cs)) t.dense = std::move(*r);
  });
  return t;
}

// The rows of one size: GPU and CPU, culled and dense, and how they compare.
void sizeRows(const std::string& tag, const char* target, const char* ratioTarget, const GpuTimes& gpu, const CpuTimes& cpu, bool withDense,
              int threads, std::vector<Row>& rows) {
  const g::GpuPolygonizeStats& gpuCulled = gpu.culled;
  const g::GpuPolygonizeStats& gpuDense = gpu.dense;
  const double msGpu = gpu.ms, msCpu = cpu.ms;
  const std::string th = std::to_string(threads) + " threads";
  char note[320];
  std::snprintf(note, sizeof note,
                "latency, wall, warm (median after a warm-up), polygonise + read-back (%.2f ms of it); processor "
                "time %.1f ms (all threads: %s of the device); %u tris, %u/%u blocks evaluated, load %s",
                gpu.readBackMs, gpu.cpuMs, th.c_str(), gpuCulled.triangles, gpuCulled.blocksActive,
                gpuCulled.blocksTotal, loadAverage().c_str());
  rows.push_back({tag + " GPU culled", msGpu, "ms", target, note});
  std::snprintf(note, sizeof note, "timestamps, medians: upload %.2f, coarse %.2f, compact %.2f, field+cells %.2f, scan %.2f, emit %.2f ms; no read-back",
                gpuCulled.passMs[0], gpuCulled.passMs[1], gpuCulled.passMs[2], gpuCulled.passMs[3],
                gpuCulled.passMs[4], gpuCulled.passMs[5]);
  double gpuSum = 0.0;
  for (double x : gpuCulled.passMs) gpuSum += x;
  rows.push_back({tag + " GPU culled, GPU time", gpuSum, "ms", "", note});
  rows.push_back({tag + " GPU culled, processor time", gpu.cpuMs, "ms", "",
                  "mean per run incl. read-back, all threads of the process (" + th + " of the device), warm"});
  if (withDense) {
    std::snprintf(note, sizeof note, "wall, warm, incl. read-back; %u tris; passes %.2f %.2f %.2f %.2f %.2f %.2f ms", gpuDense.triangles,
                  gpuDense.passMs[0], gpuDense.passMs[1], gpuDense.passMs[2], gpuDense.passMs[3], gpuDense.passMs[4],
                  gpuDense.passMs[5]);
    rows.push_back({tag + " GPU dense", gpu.denseMs, "ms", "", note});
    rows.push_back({tag + " GPU dense/culled", gpu.denseMs / msGpu, "ratio", "", ""});
  }
  rows.push_back({tag + " GPU triangles/s", gpuCulled.triangles / (msGpu * 1e-3), "tris/s", "", "one polygonisation at a time (latency-bound), incl. read-back"});
  const PolygonizeResult& cpuCulled = cpu.culled;
  std::snprintf(note, sizeof note,
                "latency, wall, warm (median after a warm-up), %s; processor time %.1f ms; %zu tris, %zu/%zu blocks "
                "evaluated, %zu cells, %zu points, %zu pairs",
                th.c_str(), cpu.cpuMs, cpuCulled.mesh.triangleCount(), cpuCulled.stats.blocksEvaluated,
                cpuCulled.stats.blocksTotal, cpuCulled.stats.cellsVisited, cpuCulled.stats.pointsEvaluated,
                cpuCulled.stats.primitiveEvaluations);
  rows.push_back({tag + " CPU culled", msCpu, "ms", "", note});
  rows.push_back({tag + " CPU culled, processor time", cpu.cpuMs, "ms", "", "mean per run, all " + th + ", warm"});
  if (withDense) {
    rows.push_back({tag + " CPU dense", cpu.denseMs, "ms", "", "wall, warm, " + th + ", " + std::to_string(cpu.dense.mesh.triangleCount()) + " tris"});
    rows.push_back({tag + " CPU dense/culled", cpu.denseMs / msCpu, "ratio", "", ""});
  }
  rows.push_back({tag + " CPU triangles/s", cpuCulled.mesh.triangleCount() / (msCpu * 1e-3), "tris/s", "", "one polygonisation at a time, " + th});
  rows.push_back({tag + " GPU / CPU time", msGpu / msCpu, "ratio", ratioTarget, "wall, culled, same field and grid, both " + th + ", GPU incl. read-back"});
  double triDiff = std::abs(double(gpuCulled.triangles) - double(cpuCulled.mesh.triangleCount())) /
                   std::max<double>(1.0, double(cpuCulled.mesh.triangleCount()));
  rows.push_back({tag + " GPU vs CPU triangle difference", 100.0 * triDiff, "%", "<= 0.5 %", ""});
}

// One program at one resolution, GPU (polygonise + read-back) against the CPU on as many threads
// as the device, both warm, with the program's own bounds: the BlobTree preview's two backends.
void programRows(g::GpuPolygonizer& poly, const std::string& tag, const FieldProgram& program, int res, int reps,
                 int threads, const char* target, std::vector<Row>& rows) {
  const std::string th = std::to_string(threads) + " threads";
  const g::GpuField field = g::GpuField::single(program);
  if (std::string why = g::GpuPolygonizer::unsupported(field); !why.empty()) {
    rows.push_back({tag + " GPU refused", 0, "", target, why});
    return;
  }
  g::GpuPolygonizeSettings gs;
  gs.resolution = res;
  g::GpuPolygonizeStats st;
  std::string error;
  auto runGpu = [&] {
    auto r = poly.polygonize(field, gs);
    if (!r) {
      error = r.error();
      return;
    }
    st = *r;
    if (auto mesh = poly.readBack(); !mesh) error = mesh.error();
  };
  const double msGpu = animorph::bench::medianMs(reps, runGpu);
  const double cpuGpu = processCpuMs([&] { runGpu(); });
  PolygonizeSettings cs;
  cs.resolution = res;
  cs.threads = threads;
  PolygonizeResult cpu;
  auto runCpu = [&] {
    if (auto r = polygonize(program, cs)) cpu = std::move(*r);
  };
  const double msCpu = animorph::bench::medianMs(reps, runCpu);
  const double cpuCpu = processCpuMs(runCpu);
  if (!error.empty()) {
    rows.push_back({tag + " GPU failed", 0, "", target, error});
    return;
  }
  char note[360];
  std::snprintf(note, sizeof note,
                "latency, wall, warm, polygonise + read-back; processor time %.1f ms (all threads, %s of the "
                "device); %u tris, %u/%u blocks evaluated; cells %.2f, emit %.2f ms",
                cpuGpu, th.c_str(), st.triangles, st.blocksActive, st.blocksTotal, st.passMs[3], st.passMs[5]);
  rows.push_back({tag + " GPU culled", msGpu, "ms", "", note});
  std::snprintf(note, sizeof note, "latency, wall, warm, %s; processor time %.1f ms; %zu tris, %zu primitives",
                th.c_str(), cpuCpu, cpu.mesh.triangleCount(), program.primitiveCount());
  rows.push_back({tag + " CPU culled", msCpu, "ms", "", note});
  rows.push_back({tag + " GPU / CPU time", msGpu / msCpu, "ratio", target, "wall, both " + th + ", GPU incl. read-back"});
}

// The host's part of a GPU frame of one program that does not depend on the grid: packing it for
// the shaders (every record) and finding its pipeline variant (every frame of the editor's preview:
// GpuPolygonizer::ready, which packed the whole program for it until 2026-11-29 and now walks
// its ops: fieldProgramsShape). Latency, wall, one thread, warm.
void hostRows(const std::string& tag, const FieldProgram& program, std::vector<Row>& rows) {
  size_t words = 0;
  const double pack = animorph::bench::medianMs(5, [&] {
    if (auto pk = g::packFieldPrograms(program)) words = pk->pool.size() + pk->bounds.size();
  });
  size_t shapeWords = 0;
  const double shape = animorph::bench::medianMs(5, [&] { shapeWords = g::fieldProgramsShape(program).poolWords; });
  rows.push_back({tag + " host: pack for the GPU", pack, "ms", "",
                  "each record; " + std::to_string(words * 16 / 1024) + " KiB uploaded (pool and bounds)"});
  Bounds tight;
  const double bounds = animorph::bench::medianMs(3, [&] { tight = program.tightBounds(); });
  rows.push_back({tag + " host: grid bounds (tightBounds)", bounds, "ms", "",
                  std::string("each record without a bounds override (the CPU polygoniser's grid rule)") +
                      (tight.empty() ? "; empty" : "")});
  rows.push_back({tag + " host: pipeline variant lookup", shape, "ms", "",
                  "each preview frame (ready, prewarm): the programs' shape (" + std::to_string(shapeWords) +
                      " pool words); was a whole pack (the row above)"});
}

// The demo BlobTree creature (frames, so affine maps: the point path, not line groups) at the
// editor's scrubbing resolution, and the animorphosis demo's dragon and C(t) (thousands of
// primitives, each under its own frame).
void blobTreeRows(g::GpuPolygonizer& poly, int threads, bool quick, std::vector<Row>& rows) {
  const FieldProgram creature = compileFieldProgram(makeBlobCreature(), 0.5);
  programRows(poly, "blob creature 96^3", creature, 96, 5, threads, "<= 1.5", rows);
  auto project = makeAnimorphosisDemoProject();
  auto c = project ? projectGenericTree(*project) : Result<GenericTree>(Error{project.error()});
  if (!c) {
    rows.push_back({"animorphosis demo: skipped", 0, "", "", c.error()});
    return;
  }
  const FieldProgram dragon = compileFieldProgram(project->actors[1].blobTree, 0.5);
  programRows(poly, std::string("demo dragon ") + (quick ? "64^3" : "128^3"), dragon, quick ? 64 : 128, quick ? 1 : 3,
              threads, "<= 1.5", rows);
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  const FieldProgram ct = compileGeneric(*c, animorphosisTiming(*project), mid);
  hostRows("demo C(t) at the middle", ct, rows);
  programRows(poly, std::string("demo C(t) at the middle ") + (quick ? "48^3" : "96^3"), ct, quick ? 48 : 96,
              quick ? 1 : 3, threads, "<= 1.5", rows);
}

// Every primitive of the subtree painted with one of four colours by its id (deterministic).
void paintById(BlobNode& n) {
  const glm::vec3 palette[4] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.2f, 0.9f}, {0.2f, 0.8f, 0.1f}, {0.95f, 0.9f, 0.3f}};
  if (paramIndex(n.type, "color") >= 0) n.vec3Param("color") = Vec3Track(palette[size_t(n.id) % 4]);
  for (BlobNode& c : n.children) paintById(c);
}

// The median over reps of poly polygonising field under gs and reading the mesh back (latency,
// wall, warm); vertices gets the mesh's count. Empty error, or why a run failed (the colour pass
// not running as gs.colors asks included).
double timedGpuColors(g::GpuPolygonizer& poly, const g::GpuField& field, const g::GpuPolygonizeSettings& gs,
                      int reps, uint32_t& vertices, std::string& error) {
  return animorph::bench::medianMs(reps, [&] {
    auto r = poly.polygonize(field, gs);
    if (!r) error = r.error();
    else if (r->colors != gs.colors) error = "the colour pass did not run as asked";
    else vertices = r->vertices;
    if (auto mesh = poly.readBack(); !mesh) error = mesh.error();
  });
}

// The colour pass's cost with per-region programs forced on (the passes and the colour pass walk each
// region's list, docs/gpu-polygonizer.md "Colour"): field under gs with colours and without, rows
// tagged tag. Where Auto already walks lists these repeat the rows above.
void regionListColorRows(g::GpuPolygonizer& poly, const g::GpuField& field, g::GpuPolygonizeSettings gs, int reps,
                         const std::string& tag, std::vector<Row>& rows) {
  gs.regionPrograms = g::GpuPolygonizeSettings::RegionPrograms::On;
  double ms[2] = {0, 0};
  uint32_t vertices = 0;
  bool colorLists = false;
  for (int colored = 0; colored < 2; ++colored) {
    gs.colors = colored != 0;
    std::string error;
    ms[colored] = timedGpuColors(poly, field, gs, reps, vertices, error);
    if (!error.empty()) {
      rows.push_back({tag + " GPU region lists on failed", 0, "", "", error});
      return;
    }
    if (colored) colorLists = poly.lastStats().colorRegionLists;
  }
  rows.push_back({tag + " GPU lists on, colours", ms[1], "ms", "",
                  std::string("latency, wall, warm, region programs On, the colour pass ") +
                      (colorLists ? "walking region lists" : "walking the whole program")});
  rows.push_back({tag + " GPU lists on, no colours", ms[0], "ms", "", "the same, colour pass off (baseline)"});
  rows.push_back({tag + " GPU lists on, colours / none", ms[1] / ms[0], "ratio", "", ""});
}

// The colour stream's cost (docs/gpu-polygonizer.md, "Colour"): the blob creature painted part by
// part, polygonised with and without vertex colours on the GPU (the colour pass) and on the CPU (per
// block), same run, same grid.
void colorRows(g::GpuPolygonizer& poly, int threads, bool quick, std::vector<Row>& rows) {
  BlobTree tree = makeBlobCreature();
  paintById(tree.root);
  const FieldProgram painted = compileFieldProgram(tree, 0.5);
  const int res = quick ? 64 : 96, reps = quick ? 3 : 5;
  const std::string tag = "painted blob creature " + std::to_string(res) + "^3";
  const std::string th = std::to_string(threads) + " threads";
  double gpuMs[2] = {0, 0}, cpuMs[2] = {0, 0};
  uint32_t vertices = 0;
  for (int colored = 0; colored < 2; ++colored) {
    g::GpuPolygonizeSettings gs;
    gs.resolution = res;
    gs.colors = colored != 0;
    std::string error;
    gpuMs[colored] = timedGpuColors(poly, g::GpuField::single(painted), gs, reps, vertices, error);
    if (!error.empty()) {
      rows.push_back({tag + " GPU failed", 0, "", "", error});
      return;
    }
    PolygonizeSettings cs;
    cs.resolution = res;
    cs.threads = threads;
    cs.colors = colored != 0;
    cpuMs[colored] = animorph::bench::medianMs(reps, [&] { (void)polygonize(painted, cs); });
  }
  const std::string note = "latency, wall, warm, median of " + std::to_string(reps) + ", polygonise + read-back, " +
                           std::to_string(vertices) + " vertices";
  rows.push_back({tag + " GPU, colours", gpuMs[1], "ms", "", note});
  rows.push_back({tag + " GPU, no colours", gpuMs[0], "ms", "", "the same, colour pass off (baseline)"});
  rows.push_back({tag + " GPU colours / none", gpuMs[1] / gpuMs[0], "ratio", "", ""});
  {
    g::GpuPolygonizeSettings gs;
    gs.resolution = res;
    regionListColorRows(poly, g::GpuField::single(painted), gs, reps, tag, rows);
  }
  rows.push_back({tag + " CPU, colours", cpuMs[1], "ms", "", "latency, wall, warm, " + th});
  rows.push_back({tag + " CPU, no colours", cpuMs[0], "ms", "", "the same, no colours (baseline)"});
  rows.push_back({tag + " CPU colours / none", cpuMs[1] / cpuMs[0], "ratio", "", ""});
}

// The demo morph's implicit stage half way (creature -> gear, 96^3 or 48^3 quick): the GPU with its
// colour program (GpuField::colors, the preview's path) and without, and the CPU worker's
// polygonisation with its colour program and without (the preview's other backend).
void morphColorRows(g::GpuPolygonizer& poly, int threads, bool quick, std::vector<Row>& rows) {
  const bench::DemoMorphDir demo;
  if (!demo.project) {
    rows.push_back({"demo morph colours: skipped", 0, "", "", "the demo morph could not be made"});
    return;
  }
  AssetCache assets;
  auto rt = prepareMorph(*demo.project, demo.dir, assets);
  if (!rt) {
    rows.push_back({"demo morph colours: skipped", 0, "", "", rt.error()});
    return;
  }
  const int res = quick ? 48 : 96, reps = quick ? 3 : 5;
  const MorphMarkers& k = (*rt)->setup.markers;
  const double t = (*rt)->timeline.frameToSec(0.5 * (k.b + k.c));
  const MorphImplicitField f = morphImplicitField(**rt, t, res, 0.5);
  if (!f.colorProgram) {
    rows.push_back({"demo morph colours: skipped", 0, "", "", "the demo morph has no colours"});
    return;
  }
  const std::string tag = "demo morph B..C half way " + std::to_string(res) + "^3";
  double gpuMs[2] = {0, 0}, cpuMs[2] = {0, 0};
  uint32_t vertices = 0;
  bool fieldLists = false, colorLists = false;
  for (int colored = 0; colored < 2; ++colored) {
    g::GpuField field = g::GpuField::single(f.program);
    if (colored) field.colors = f.colorProgram.get();
    g::GpuPolygonizeSettings gs;
    gs.resolution = res;
    gs.bounds = f.bounds;
    gs.colors = colored != 0;
    std::string error;
    gpuMs[colored] = timedGpuColors(poly, field, gs, reps, vertices, error);
    if (!error.empty()) {
      rows.push_back({tag + " GPU failed", 0, "", "", error});
      return;
    }
    fieldLists = poly.lastStats().regionLists;
    if (colored) colorLists = poly.lastStats().colorRegionLists;
    PolygonizeSettings cs;
    cs.resolution = res;
    cs.threads = threads;
    cs.bounds = f.bounds;
    cs.colors = colored != 0;
    cs.colorProgram = f.colorProgram.get();
    cpuMs[colored] = animorph::bench::medianMs(reps, [&] { (void)polygonize(f.program, cs); });
  }
  rows.push_back({tag + " GPU, colour program", gpuMs[1], "ms", "",
                  "latency, wall, warm, polygonise + read-back, " + std::to_string(vertices) + " vertices; region lists " +
                      (fieldLists ? "on" : "off") + ", the colour pass " +
                      (colorLists ? "walking region lists" : "walking the whole colour program")});
  rows.push_back({tag + " GPU, no colours", gpuMs[0], "ms", "", "the same, colour pass off (baseline)"});
  rows.push_back({tag + " GPU colours / none", gpuMs[1] / gpuMs[0], "ratio", "", ""});
  rows.push_back({tag + " CPU, colour program", cpuMs[1], "ms", "", "latency, wall, warm, " + std::to_string(threads) + " threads"});
  rows.push_back({tag + " CPU, no colours", cpuMs[0], "ms", "", "the same, no colours (baseline)"});
  rows.push_back({tag + " GPU / CPU with colours", gpuMs[1] / cpuMs[1], "ratio", "", "the preview's two backends"});
  if (!fieldLists) {
    g::GpuField field = g::GpuField::single(f.program);
    field.colors = f.colorProgram.get();
    g::GpuPolygonizeSettings gs;
    gs.resolution = res;
    gs.bounds = f.bounds;
    regionListColorRows(poly, field, gs, reps, tag, rows);
  }
}

// A Vulkan context and a GPU polygoniser on it for a bench, with its "device" row; none where there
// is no device or the polygoniser cannot be made (a "skipped" row says why).
struct BenchDevice {
  std::unique_ptr<g::Context> ctx;
  std::unique_ptr<g::GpuPolygonizer> poly;
};
std::optional<BenchDevice> benchDevice(std::vector<Row>& rows) {
  auto ctx = g::Context::create(g::ContextSettings{});
  if (!ctx) {
    rows.push_back({"skipped", 0, "", "", "no Vulkan device: " + ctx.error()});
    return std::nullopt;
  }
  auto poly = g::GpuPolygonizer::create(**ctx);
  if (!poly) {
    rows.push_back({"skipped", 0, "", "", poly.error()});
    return std::nullopt;
  }
  rows.push_back({"device", 0, "", "", (*ctx)->deviceName() + "; load average " + loadAverage() + " at start"});
  return BenchDevice{std::move(*ctx), std::move(*poly)};
}

std::vector<Row> runGpuColor(const animorph::bench::Options& opt) {
  std::vector<Row> rows;
  std::optional<BenchDevice> dev = benchDevice(rows);
  if (!dev) return rows;
  const int threads = baselineThreads();
  colorRows(*dev->poly, threads, opt.quick, rows);
  morphColorRows(*dev->poly, threads, opt.quick, rows);
  return rows;
}

std::vector<Row> runGpuPoly(const animorph::bench::Options& opt) {
  std::vector<Row> rows;
  bool wanted = opt.gpu;
  for (const auto& f : opt.filters) wanted |= f.find("gpu") != std::string::npos;
  if (!wanted) {
    rows.push_back({"skipped", 0, "", "", "run `bench gpu` or pass --gpu"});
    return rows;
  }
  const unsigned seedA = 1u, seedB = 2u;
  const float w = 0.5f;
  FieldProgram a = standIn(seedA), b = standIn(seedB);
  FieldProgram merged = interpolatedProgram(seedA, seedB, w);
  std::optional<BenchDevice> dev = benchDevice(rows);
  if (!dev) return rows;
  const g::GpuField field = g::GpuField::interpolation(a, b, w);
  const bool withDense = !std::getenv("ANIMORPH_BENCH_GPU_NO_DENSE");
  const int threads = baselineThreads();
  for (const int res : gpuBenchSizes(opt)) {
    const char* target = res == 64 ? "<= 5 ms" : res == 128 ? "<= 30 ms" : "<= 200 ms";
    const int reps = res >= 256 ? 3 : (res >= 128 ? 5 : 9);
    const std::string tag = "40 segs morph " + std::to_string(res) + "^3";
    const GpuTimes gpu = timeGpu(*dev->poly, field, res, reps, withDense);
    if (!gpu.error.empty()) {
      rows.push_back({tag + " GPU failed", 0, "", "", gpu.error});
      continue;
    }
    const CpuTimes cpu = timeCpu(merged, res, reps, withDense, threads);
    sizeRows(tag, target, res >= 128 ? "<= 1.2" : "", gpu, cpu, withDense, threads, rows);
  }
  blobTreeRows(*dev->poly, threads, opt.quick, rows);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("gpu", "GPU vs CPU polygonisation of a 40-segment stand-in morph (needs `bench gpu` or --gpu)",
               runGpuPoly);
ANIMORPH_BENCH("gpu-color", "the GPU polygoniser's colour pass: painted BlobTree and the demo morph, with and without "
               "colours, GPU and CPU", runGpuColor);
