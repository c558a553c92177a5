// The CPU bake's cost at 256^3 against 128^3: the same frames of a character pair's implicit stage
// (B..C) baked at both sizes, as animorph-cli bake makes a frame (the field, polygonised with the
// colours, displaced by the solid noise, measured for the continuity report), with each stage's
// time and the polygoniser's own stages (poly/polygonize_stage_times.h). A surface-bound bake costs
// about 4x at twice the resolution (4x the surface cells); more means a stage grows with the volume.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <string>
#include <thread>

#include "app/cli/bench/bench.h"
#include "core/io/character_import.h"
#include "core/poly/polygonize_stage_times.h"
#include "core/poly/solid_noise.h"
#include "core/project/new_morph_project.h"
#include "core/scene/morph_runtime.h"
#include "core/standin_morph/morph_continuity.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

constexpr int kSampleFrames = 4;  // frames spread over B..C, the same at both sizes

// Wall and processor time (all threads of the process) of the stages of one size's frames.
struct StageClock {
  double fieldMs = 0.0, polygonizeMs = 0.0, noiseMs = 0.0, measureMs = 0.0, jumpMs = 0.0;
  double wallMs = 0.0, processorMs = 0.0;
  size_t triangles = 0;
  PolygonizeStageTimes poly;
};

double processorNowMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

double msSince(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - t).count();
  t = now;
  return ms;
}

// One B..C frame as the bake makes it (ProjectFrames::frame of a Morph frame with measure on, and
// the continuity meter's jump against the frame before, `previous`: replaced by this one), stage by stage.
void bakeFrame(const MorphRuntime& rt, double timeSec, int frame, int res, TriangleMesh& previous, StageClock& c) {
  auto t = std::chrono::steady_clock::now();
  const MorphImplicitField field = morphImplicitField(rt, timeSec, res, -1.0);
  c.fieldMs += msSince(t);
  PolygonizeSettings ps;  // as evaluateMorphImplicit
  ps.resolution = res;
  ps.bounds = field.bounds;
  ps.colors = field.colorProgram != nullptr;
  ps.colorProgram = field.colorProgram.get();
  auto r = polygonize(field.program, ps);
  c.polygonizeMs += msSince(t);
  if (!r) return;
  TriangleMesh mesh = std::move(r->mesh);
  displaceBySolidNoise(mesh, field.noiseAmplitude, rt.setup.noiseFrequency);
  c.noiseMs += msSince(t);
  (void)measureFrame(frame, mesh, nullptr, 0);
  c.measureMs += msSince(t);
  if (!previous.positions.empty()) (void)hausdorffDistance(previous, mesh);
  c.jumpMs += msSince(t);
  c.triangles += mesh.triangleCount();
  previous = std::move(mesh);
}

// Adds one frame's clock (its fastest repeat) into the sum of the sample frames.
void addFrame(StageClock& sum, const StageClock& f) {
  sum.fieldMs += f.fieldMs;
  sum.polygonizeMs += f.polygonizeMs;
  sum.noiseMs += f.noiseMs;
  sum.measureMs += f.measureMs;
  sum.jumpMs += f.jumpMs;
  sum.wallMs += f.wallMs;
  sum.processorMs += f.processorMs;
  sum.triangles += f.triangles;
  PolygonizeStageTimes& a = sum.poly;
  const PolygonizeStageTimes& b = f.poly;
  a.calls += b.calls;
  a.setupMs += b.setupMs;
  a.superblocksMs += b.superblocksMs;
  a.pairsMs += b.pairsMs;
  a.blocksMs += b.blocksMs;
  a.stitchMs += b.stitchMs;
  a.orphansMs += b.orphansMs;
  a.historyMs += b.historyMs;
  a.colorsMs += b.colorsMs;
  a.totalMs += b.totalMs;
  a.blocksTotal += b.blocksTotal;
  a.blocksVisited += b.blocksVisited;
  a.blocksEvaluated += b.blocksEvaluated;
  a.blocksWithSurface += b.blocksWithSurface;
}

// The sample frames at res: each frame's previous frame baked first, untimed, so that the jump is
// the continuity meter's (between consecutive frames: nearby surfaces); then the frame `repeats`
// times, its fastest repeat counted (the machine is shared: the others only add time).
StageClock bakeSamples(const MorphRuntime& rt, int res, int repeats) {
  const MorphMarkers& mk = rt.setup.markers;
  StageClock c, untimed;
  TriangleMesh previous;
  // Warm: one frame first (allocator, thread pool, caches), not counted.
  bakeFrame(rt, rt.timeline.frameToSec((mk.b + mk.c) / 2), (mk.b + mk.c) / 2, res, previous, untimed);
  for (int k = 0; k < kSampleFrames; ++k) {
    const int f = mk.b + 1 + int(double(mk.c - mk.b - 1) * (k + 0.5) / kSampleFrames);
    TriangleMesh before;
    bakeFrame(rt, rt.timeline.frameToSec(f - 1), f - 1, res, before, untimed);
    StageClock best;
    for (int r = 0; r < repeats; ++r) {
      StageClock one;
      previous = before;
      setPolygonizeStageTimes(&one.poly);
      auto w = std::chrono::steady_clock::now();
      const double p0 = processorNowMs();
      bakeFrame(rt, rt.timeline.frameToSec(f), f, res, previous, one);
      one.processorMs = processorNowMs() - p0;
      one.wallMs = msSince(w);
      setPolygonizeStageTimes(nullptr);
      if (r == 0 || one.wallMs < best.wallMs) best = one;
    }
    addFrame(c, best);
  }
  return c;
}

// A stage's wall time at both sizes (res and 2 res) and its ratio.
void stageRow(const std::string& pre, const char* stage, int res, double lo, double hi, std::vector<Row>& rows) {
  char note[200];
  std::snprintf(note, sizeof note, "wall, per frame (its fastest repeat): %d^3 %.2f ms, %d^3 %.2f ms", res,
                lo / kSampleFrames, 2 * res,
                hi / kSampleFrames);
  rows.push_back({pre + "stage " + stage + ", ratio", lo > 0.0 ? hi / lo : 0.0, "ratio", "", note});
}

void pairRows(const Project& project, const std::string& dir, const std::string& label, const bench::Options& opt,
              std::vector<Row>& rows) {
  AssetCache assets;
  auto rt = prepareMorph(project, dir, assets);
  const std::string pre = label + ": ";
  if (!rt) {
    rows.push_back({pre + "not measured", 0.0, "", "", rt.error()});
    return;
  }
  const int lo = opt.quick ? 32 : 128, hi = 2 * lo;
  const int repeats = opt.quick ? 1 : 3;
  const StageClock a = bakeSamples(**rt, lo, repeats), b = bakeSamples(**rt, hi, repeats);
  const MorphMarkers& mk = (*rt)->setup.markers;
  char note[320];
  for (const StageClock* c : {&a, &b}) {
    const int res = c == &a ? lo : hi;
    std::snprintf(note, sizeof note,
                  "%d frames spread over B..C (%d..%d), each after its previous frame (untimed), fastest of %d, "
                  "per frame; processor %.0f ms (all threads of %u); warm; %zu triangles per frame",
                  kSampleFrames, mk.b, mk.c, repeats, c->processorMs / kSampleFrames,
                  std::max(1u, std::thread::hardware_concurrency()), c->triangles / kSampleFrames);
    rows.push_back({pre + "bake B..C frame at " + std::to_string(res) + "^3 (wall)", c->wallMs / kSampleFrames, "ms",
                    "", note});
  }
  std::snprintf(note, sizeof note, "wall; processor time %.2fx; triangles %.2fx; surface-bound is about 4x",
                b.processorMs / a.processorMs, double(b.triangles) / double(std::max<size_t>(1, a.triangles)));
  rows.push_back({pre + "bake B..C cost " + std::to_string(hi) + "^3 / " + std::to_string(lo) + "^3",
                  b.wallMs / a.wallMs, "ratio", "<= 4.5", note});
  stageRow(pre, "field built", lo, a.fieldMs, b.fieldMs, rows);
  stageRow(pre, "polygonise (whole)", lo, a.polygonizeMs, b.polygonizeMs, rows);
  stageRow(pre, "polygonise: setup + history taken", lo, a.poly.setupMs, b.poly.setupMs, rows);
  stageRow(pre, "polygonise: superblock culling", lo, a.poly.superblocksMs, b.poly.superblocksMs, rows);
  stageRow(pre, "polygonise: pair lists and culling", lo, a.poly.pairsMs, b.poly.pairsMs, rows);
  stageRow(pre, "polygonise: blocks (cull, evaluate, triangulate)", lo, a.poly.blocksMs, b.poly.blocksMs, rows);
  stageRow(pre, "polygonise: stitch", lo, a.poly.stitchMs, b.poly.stitchMs, rows);
  stageRow(pre, "polygonise: orphans", lo, a.poly.orphansMs, b.poly.orphansMs, rows);
  stageRow(pre, "polygonise: colours after the mesh", lo, a.poly.colorsMs, b.poly.colorsMs, rows);
  stageRow(pre, "solid noise", lo, a.noiseMs, b.noiseMs, rows);
  stageRow(pre, "measure (volume, continuity)", lo, a.measureMs, b.measureMs, rows);
  stageRow(pre, "jump to the previous frame (Hausdorff)", lo, a.jumpMs, b.jumpMs, rows);
  std::snprintf(note, sizeof note, "blocks in the grids %zu / %zu, tested one by one %zu / %zu (%.2fx), evaluated "
                "%zu / %zu, with surface %zu / %zu (%d^3 / %d^3, %d frames)", a.poly.blocksTotal, b.poly.blocksTotal,
                a.poly.blocksVisited, b.poly.blocksVisited,
                double(b.poly.blocksVisited) / double(std::max<size_t>(1, a.poly.blocksVisited)),
                a.poly.blocksEvaluated, b.poly.blocksEvaluated, a.poly.blocksWithSurface, b.poly.blocksWithSurface, lo,
                hi, kSampleFrames);
  rows.push_back({pre + "blocks evaluated, ratio", double(b.poly.blocksEvaluated) /
                  double(std::max<size_t>(1, a.poly.blocksEvaluated)), "ratio", "", note});
}

// A pair of characters as `animorph-cli new` makes it (skeleton correspondence).
void characterPair(const std::string& dir, const std::string& src, const std::string& dst, const bench::Options& opt,
                   std::vector<Row>& rows) {
  const std::string label = src + " -> " + dst;
  auto a = importCharacter(dir + "/" + src);
  auto b = importCharacter(dir + "/" + dst);
  if (!a || !b) {
    rows.push_back({label + ": not measured", 0.0, "", "", !a ? a.error() : b.error()});
    return;
  }
  NewMorphSettings ns;
  ns.method = MorphMethod::SkeletonCorrespondence;
  auto made = makeMorphProject(*a, dir + "/" + src, *b, dir + "/" + dst, ns);
  if (!made) {
    rows.push_back({label + ": not measured", 0.0, "", "", made.error()});
    return;
  }
  pairRows(made->project, dir, label, opt, rows);
}

std::vector<Row> benchBakeScaling(const bench::Options& opt) {
  std::vector<Row> rows;
  // ANIMORPH_BENCH_PAIR_CULLING=0: the polygoniser without its pair level (as before it had one),
  // to compare the same binary both ways, runs alternating.
  const char* pairs = std::getenv("ANIMORPH_BENCH_PAIR_CULLING");
  const bool pairCulling = !(pairs && std::string(pairs) == "0");
  setPolygonizePairCulling(pairCulling);
  if (!pairCulling) rows.push_back({"pair culling off (ANIMORPH_BENCH_PAIR_CULLING=0)", 0.0, "", "", ""});
  const std::string source = ANIMORPH_SOURCE_DIR;
  characterPair(source + "/../shared/assets", "tentacle.glb", "plate.glb", opt, rows);
  // Characters exported by Blender (tests/tools/make_test_characters.py, made by a build).
  const char* env = std::getenv("ANIMORPH_TEST_CHARACTERS");
  const std::string made = env ? env : source + "/build/test_characters";
  characterPair(made, "humanoid_m.glb", "quadruped_m.glb", opt, rows);
  characterPair(made, "quadruped_cm.fbx", "tentacle_m.glb", opt, rows);
  setPolygonizePairCulling(true);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("bake-scaling",
               "CPU bake of B..C frames of character pairs at 128^3 and 256^3: cost ratio and per-stage times",
               benchBakeScaling);
