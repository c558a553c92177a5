// Benchmarks of the skinned-mesh morph: stand-in fitting + projection of a
// ~50k-vertex character, the CPU transition per frame, baking the demo
// creature -> gear morph, and the seams at markers B and C.
#include <chrono>
#include <cstdio>

#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_demo_morph.h"
#include "app/cli/bench/bench_gpu_transition.h"
#include "demo/dense.h"
#include "core/scene/morph_runtime.h"
#include "core/rig/pose.h"
#include "core/rig/skinning.h"
#include "demo/rigged_figure.h"
#include "core/standin/fit_standin.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

double sinceMs(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The CPU transition per frame (plain, with colour, with re-projection) against plain skinning,
// and the GPU transition rows, on the dense character and its stand-in.
void transitionRows(const bench::Options& opt, const Character& dense, const FitResult& fitted,
                    const StandinBinding& binding, std::vector<Row>& rows) {
  const size_t verts = dense.totalVertices();
  char note[160];
  const AnimationClip* clip = dense.clips.empty() ? nullptr : &dense.clips[0];
  std::vector<float> alpha(verts, 0.5f);
  std::vector<glm::vec3> pos, nrm;
  float t = 0.0f;
  const double plainMs = bench::medianMs(opt.quick ? 5 : 21, [&] {
    t += 0.04f;
    const auto globals = poseGlobals(dense, clip, t);
    evaluateTransition(dense, binding, globals, glm::mat4(1.0f), alpha, nullptr, nullptr, {}, pos, nrm);
  });
  // Baseline in the same run: plain CPU skinning (rig/skinning.h, one thread) of the same mesh.
  std::vector<glm::vec3> sp, sn;
  const double skinMs = bench::medianMs(opt.quick ? 5 : 21, [&] {
    t += 0.04f;
    const auto globals = poseGlobals(dense, clip, t);
    const int node = dense.meshNodes().front();
    skinMesh(dense.meshes[size_t(dense.nodes[size_t(node)].mesh)], jointMatrices(dense, node, globals), sp, sn);
  });
  std::snprintf(note, sizeof note, "%zu vertices, alpha 0.5, no re-projection; plain skinMesh %.2f ms (%.2fx)", verts,
                skinMs, plainMs / skinMs);
  rows.push_back({"transition per frame (CPU)", plainMs, "ms", "<= 2 ms at 50k vertices", note});
  // With colour: the vertices' colours faded into the stand-in's (transitionColors), as a
  // coloured character's transition frame adds to the same work.
  StandinBinding coloured = binding;
  coloured.vertexColors.assign(verts, glm::vec4(0.8f, 0.5f, 0.2f, 1.0f));
  coloured.standinColors.assign(verts, glm::vec4(0.2f, 0.5f, 0.8f, 1.0f));
  std::vector<glm::vec4> colors;
  const double colourMs = bench::medianMs(opt.quick ? 5 : 21, [&] {
    t += 0.04f;
    const auto globals = poseGlobals(dense, clip, t);
    evaluateTransition(dense, coloured, globals, glm::mat4(1.0f), alpha, nullptr, nullptr, {}, pos, nrm);
    transitionColors(coloured, alpha, colors);
  });
  const double againMs = bench::medianMs(opt.quick ? 5 : 21, [&] {
    t += 0.04f;
    const auto globals = poseGlobals(dense, clip, t);
    evaluateTransition(dense, binding, globals, glm::mat4(1.0f), alpha, nullptr, nullptr, {}, pos, nrm);
  });
  std::snprintf(note, sizeof note, "%zu vertices, alpha 0.5, all threads, wall time; without colour in the same run "
                "%.2f ms (%+.1f %%)", verts, againMs, 100.0 * (colourMs / againMs - 1.0));
  rows.push_back({"transition per frame with colour (CPU)", colourMs, "ms", "<= 1.1x without colour", note});
  std::fill(alpha.begin(), alpha.end(), 0.9f);
  const double reprojMs = bench::medianMs(opt.quick ? 3 : 9, [&] {
    t += 0.04f;
    const auto globals = poseGlobals(dense, clip, t);
    const auto segs = poseStandin(fitted.standin, globals, glm::mat4(1.0f));
    const FieldProgram prog = standinProgram(fitted.standin.kind, fitted.standin.sharpness, segs);
    evaluateTransition(dense, binding, globals, glm::mat4(1.0f), alpha, &prog, &segs, {}, pos, nrm);
  });
  std::snprintf(note, sizeof note, "%zu vertices, alpha 0.9: every vertex re-projected onto the posed field", verts);
  rows.push_back({"transition per frame with re-projection", reprojMs, "ms", "", note});
  for (Row& r : bench::gpuTransitionRows(opt, dense, fitted.standin, binding)) rows.push_back(std::move(r));

}

// Baking the demo creature -> gear morph over A..D, and the seams at B and C.
void demoBakeRows(const bench::Options& opt, std::vector<Row>& rows) {
  char note[160];
  const bench::DemoMorphDir demo;
  AssetCache assets;
  if (demo.project) {
    const Project& project = *demo.project;
    auto rt = prepareMorph(project, demo.dir, assets);
    if (rt) {
      const int frames = opt.quick ? 20 : 100;
      const int res = 64;
      const MorphMarkers& mk = project.morph.markers;
      // 100 frames spread over A..D (the stages that cost), ~2/3 implicit.
      const auto t0 = std::chrono::steady_clock::now();
      size_t implicitFrames = 0;
      for (int k = 0; k < frames; ++k) {
        const double f = mk.a + double(mk.d - mk.a) * k / std::max(1, frames - 1);
        MorphFrameSettings mfs;
        mfs.resolution = res;
        auto fr = evaluateMorphFrame(**rt, f / project.timeline.fps, mfs);
        if (fr && fr->stage == MorphStage::Morph) ++implicitFrames;
      }
      const double bakeMs = sinceMs(t0);
      std::snprintf(note, sizeof note, "%d frames over A..D (%zu implicit) at %d^3, meshes kept in memory", frames,
                    implicitFrames, res);
      rows.push_back({"bake creature -> gear", bakeMs / 1000.0, "s", "<= 10 s for 100 frames at 64^3", note});
      for (bool atB : {true, false}) {
        auto gap = measureSeamGap(**rt, atB, res);
        if (!gap) continue;
        std::snprintf(note, sizeof note, "max %.4f m, mean %.4f m; cell %.4f m", gap->maxDistance, gap->meanDistance,
                      gap->cellSize);
        rows.push_back({atB ? "seam gap at B / half cell" : "seam gap at C / half cell",
                        gap->maxDistance / (0.5 * gap->cellSize), "ratio", "<= 1", note});
      }
    }
  }
}

std::vector<Row> benchMorph(const bench::Options& opt) {
  std::vector<Row> rows;
  // ---- fit + projection of a dense character
  const size_t tris = opt.quick ? 20000 : 100000;
  const Character dense = makeDenseCharacter(tris);
  const size_t verts = dense.totalVertices();
  auto t0 = std::chrono::steady_clock::now();
  FitSettings fs;
  fs.measure = false;
  auto fit = fitStandin(dense, fs);
  const double fitMs = sinceMs(t0);
  if (!fit) {
    std::fprintf(stderr, "bench morph: %s\n", fit.error().c_str());
    return rows;
  }
  t0 = std::chrono::steady_clock::now();
  const StandinBinding binding = bindToStandin(dense, fit->standin, nullptr, 0.0f, ProjectionSettings{});
  const double projMs = sinceMs(t0);
  char note[160];
  std::snprintf(note, sizeof note, "%zu vertices, %zu segments; fit %.0f ms + projection %.0f ms; %zu fallbacks, %zu failures",
                verts, fit->standin.segments.size(), fitMs, projMs, binding.stats.fallbacks, binding.stats.failures);
  rows.push_back({"fit + projection (dense character)", fitMs + projMs, "ms", "<= 1000 ms at 50k vertices", note});

  // ---- fit with its quality report (error per segment, far share, polygonised
  // components) against the previous fitter measuring the error only; and the
  // rigged figure 60 units tall (helper bones, node scales, face and finger bones).
  FitSettings before;
  before.bridgeHelpers = false;
  before.mergeSmallBones = false;
  before.repair.enabled = false;
  before.quality.topologyResolution = 0;
  const double beforeMs = bench::medianMs(3, [&] { (void)fitStandin(dense, before); });
  FitResult full;
  const double fullMs = bench::medianMs(3, [&] { full = *fitStandin(dense, FitSettings{}); });
  std::snprintf(note, sizeof note, "%zu vertices; baseline (previous fitter, error only) %.0f ms; %d stand-in piece(s)",
                verts, beforeMs, full.report.standinComponents);
  rows.push_back({"fit + quality report (dense character)", fullMs, "ms", "<= 1000 ms at 50k vertices", note});
  RiggedFigureOptions fo;
  fo.height = 60.0f;
  const Character figure = makeRiggedFigure(fo);
  FitResult fig;
  const double figBeforeMs = bench::medianMs(3, [&] { (void)fitStandin(figure, before); });
  const double figMs = bench::medianMs(3, [&] { fig = *fitStandin(figure, FitSettings{}); });
  std::snprintf(note, sizeof note, "%zu vertices, %zu joints; baseline %.0f ms; %zu segments, %d piece(s), mean %.2f %%",
                figure.totalVertices(), figure.totalJoints(), figBeforeMs, fig.report.segments,
                fig.report.standinComponents, 100.0 * fig.report.meanError);
  rows.push_back({"fit + quality report (rigged figure, 60 units)", figMs, "ms", "<= 1000 ms", note});

  transitionRows(opt, dense, *fit, binding, rows);
  demoBakeRows(opt, rows);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("morph", "stand-in fit + projection, CPU transition, bake creature -> gear, seams", benchMorph);
