// Popping through a morph: the largest frame-to-frame change of volume and of
// Hausdorff distance through A..D (and the volume change within B..C) of the
// demo creature -> gear morph and of tentacle.glb -> plate.glb (shared assets),
// relative to the same figures of the two characters' own motion (skinned, no
// morph), for the unbounded interpolation (the old blend), the bounded one (the
// default), space-time blending and skeleton correspondence (combined with
// either; and without the transitions' stand-in core, the seam at C before it),
// with what a B..C frame costs, all in the same run. Frames are measured as what is
// seen: a collapse or expansion frame's visible surface (core/scene/visible_surface.h), so
// the Hausdorff row is the continuity ratio (core/scene/morph_smoothness.h).
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_demo_morph.h"
#include "core/standin_morph/morph_continuity.h"
#include "core/io/gltf_import.h"
#include "core/scene/morph_runtime.h"
#include "core/project/new_morph_project.h"
#include "core/scene/morph_smoothness.h"
#include "core/scene/visible_surface.h"

namespace {

using namespace animorph;
using animorph::bench::Row;

// The largest volume change between consecutive frames both within [b, c] (the implicit stage alone).
double largestVolumeChangeWithin(const ContinuitySummary& s, int b, int c, int& at) {
  double best = 0.0;
  for (size_t i = 1; i < s.frames.size(); ++i) {
    const FrameMeasure &p = s.frames[i - 1], &f = s.frames[i];
    if (p.frame < b || f.frame > c) continue;
    const double d = relativeVolumeChange(p.volume, f.volume);
    if (d > best) best = d, at = f.frame;
  }
  return best;
}

// Rows of one morph pair (label "" for the demo, whose row names stay as they were): the
// characters' own motion, then per method the largest changes through A..D and within B..C,
// and what a B..C frame costs (field built and polygonised, median over the stage's frames).
void pairRows(const Project& base, const std::string& dir, const std::string& label, const bench::Options& opt,
              std::vector<Row>& rows) {
  const int res = opt.quick ? 32 : 64;
  const MorphMarkers& mk = base.morph.markers;
  const int first = opt.quick ? mk.b - 2 : mk.a, last = opt.quick ? mk.c + 2 : mk.d;
  const std::string pre = label.empty() ? "" : label + ": ";
  AssetCache assets;
  char note[240];
  // The characters' own motion over the same frames (alpha 0: plain skinning).
  double motionH = 0.0, motionV = 0.0;
  if (auto rt = prepareMorph(base, dir, assets)) {
    for (bool target : {false, true}) {
      const ContinuitySummary s = measureContinuity(first, last, [&](int f) {
        return evaluateMorphTransition(**rt, base.timeline.frameToSec(f), target, target ? 1.0 : 0.0, {}).mesh;
      });
      motionH = std::max(motionH, s.maxHausdorff);
      motionV = std::max(motionV, s.maxVolumeChange);
    }
  }
  std::snprintf(note, sizeof note, "frames %d..%d, %s and %s skinned alone: largest volume change %.2f%%", first, last,
                base.morph.sourceActorId.c_str(), base.morph.targetActorId.c_str(), 100.0 * motionV);
  rows.push_back({pre + "motion alone: largest frame-to-frame Hausdorff", motionH, "m", "", note});
  struct Variant {
    const char* name;
    MorphMethod method;
    float bound;
    MorphMethod blend;
    bool core = true;  // the stand-in core in the transitions (false: the mesh alone, as before)
  };
  const Variant variants[] = {
      {"interpolation, unbounded (old blend)", MorphMethod::Interpolation, 0.0f, MorphMethod::Interpolation},
      {"interpolation, bounded (default)", MorphMethod::Interpolation, kDefaultInterpolationBound,
       MorphMethod::Interpolation},
      {"space-time blending", MorphMethod::SpaceTime, kDefaultInterpolationBound, MorphMethod::Interpolation},
      {"skeleton correspondence + interpolation, no stand-in core (before)", MorphMethod::SkeletonCorrespondence,
       kDefaultInterpolationBound, MorphMethod::Interpolation, false},
      {"skeleton correspondence + interpolation", MorphMethod::SkeletonCorrespondence, kDefaultInterpolationBound,
       MorphMethod::Interpolation},
      {"skeleton correspondence + space-time", MorphMethod::SkeletonCorrespondence, kDefaultInterpolationBound,
       MorphMethod::SpaceTime}};
  for (const Variant& v : variants) {
    Project p = base;
    p.morph.method = v.method;
    p.morph.interpolationBound = v.bound;
    p.morph.correspondenceBlend = v.blend;
    auto rt = prepareMorph(p, dir, assets);
    if (!rt) continue;
    MorphFrameSettings fs;
    fs.resolution = res;
    fs.standinCore = v.core;
    std::vector<double> stageMs;
    const ContinuitySummary s = measureContinuity(first, last, [&](int f) {
      const auto t0 = std::chrono::steady_clock::now();
      auto fr = evaluateMorphFrame(**rt, p.timeline.frameToSec(f), fs);
      if (fr && fr->stage == MorphStage::Morph)
        stageMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      if (!fr) return FrameShape{};
      return fr->coreTriangles > 0 ? FrameShape(visibleSurface(**rt, *fr)) : FrameShape(std::move(fr->mesh));
    });
    const size_t defects = continuityDefects(s.frames).size();
    std::snprintf(note, sizeof note, "at frame %d; %d^3; %zu empty frames, %zu frames over %.0f%%", s.maxVolumeFrame,
                  res, s.emptyFrames, defects, 100.0 * kMaxFrameVolumeChange);
    rows.push_back({pre + "largest volume change A..D: " + v.name, s.maxVolumeChange, "ratio", "", note});
    std::snprintf(note, sizeof note, "%.4f m at frame %d / motion alone %.4f m", s.maxHausdorff, s.maxHausdorffFrame,
                  motionH);
    rows.push_back({pre + "continuity ratio A..D (visible surface's largest Hausdorff / motion): " + v.name,
                    motionH > 0.0 ? s.maxHausdorff / motionH : 0.0, "ratio",
                    std::string("<= ") + std::to_string(int(kMaxContinuityRatio)), note});
    int at = 0;
    const double inside = largestVolumeChangeWithin(s, mk.b, mk.c, at);
    std::snprintf(note, sizeof note, "at frame %d (B %d, C %d; the seams with the transitions left out)", at, mk.b,
                  mk.c);
    rows.push_back({pre + "largest volume change B..C: " + v.name, inside, "ratio", "", note});
    std::sort(stageMs.begin(), stageMs.end());
    std::snprintf(note, sizeof note, "median over %zu B..C frames at %d^3 (field + polygonisation, all threads)",
                  stageMs.size(), res);
    rows.push_back({pre + "B..C frame cost: " + v.name, stageMs.empty() ? 0.0 : stageMs[stageMs.size() / 2], "ms", "",
                    note});
  }
}

std::vector<Row> benchContinuity(const bench::Options& opt) {
  std::vector<Row> rows;
  const bench::DemoMorphDir demo;
  if (demo.project) pairRows(*demo.project, demo.dir, "", opt, rows);
  // The shared assets (tentacle.glb -> plate.glb, as `new` makes it), when the checkout has them.
  const std::string assets = std::string(ANIMORPH_SOURCE_DIR) + "/../shared/assets";
  auto tentacle = importGltf(assets + "/tentacle.glb");
  auto plate = importGltf(assets + "/plate.glb");
  if (!tentacle || !plate) {
    rows.push_back({"tentacle -> plate: not measured", 0.0, "", "", assets + "/tentacle.glb or plate.glb missing"});
    return rows;
  }
  NewMorphSettings ns;
  ns.method = MorphMethod::SkeletonCorrespondence;
  auto made = makeMorphProject(*tentacle, assets + "/tentacle.glb", *plate, assets + "/plate.glb", ns);
  if (made) pairRows(made->project, assets, "tentacle -> plate", opt, rows);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("morph-continuity",
               "popping through A..D: largest frame-to-frame volume change and Hausdorff distance and B..C frame cost per morph method",
               benchContinuity);
