// Popping through a morph: the largest frame-to-frame change of volume and of
// Hausdorff distance through A..D (and the volume change within B..C) of the
// demo creature -> gear morph, relative to the same figures of the two
// characters' own motion (skinned, no morph), for the unbounded interpolation
// (the old blend), the bounded one (the default) and space-time blending,
// all in the same run.
#include <cstdio>

#include "cli/bench/bench.h"
#include "cli/bench/bench_demo_morph.h"
#include "morph/morph_continuity.h"
#include "morph/morph_runtime.h"

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

std::vector<Row> benchContinuity(const bench::Options& opt) {
  std::vector<Row> rows;
  const bench::DemoMorphDir demo;
  const std::string& dir = demo.dir;
  const int res = opt.quick ? 32 : 64;
  if (demo.project) {
    const Project& base = *demo.project;
    const MorphMarkers& mk = base.morph.markers;
    const int first = opt.quick ? mk.b - 2 : mk.a, last = opt.quick ? mk.c + 2 : mk.d;
    AssetCache assets;
    char note[200];
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
    std::snprintf(note, sizeof note, "frames %d..%d, creature and gear skinned alone: largest volume change %.2f%%",
                  first, last, 100.0 * motionV);
    rows.push_back({"motion alone: largest frame-to-frame Hausdorff", motionH, "m", "", note});
    struct Variant {
      const char* name;
      MorphMethod method;
      float bound;
    };
    const Variant variants[] = {{"interpolation, unbounded (old blend)", MorphMethod::Interpolation, 0.0f},
                                {"interpolation, bounded (default)", MorphMethod::Interpolation,
                                 kDefaultInterpolationBound},
                                {"space-time blending", MorphMethod::SpaceTime, kDefaultInterpolationBound}};
    for (const Variant& v : variants) {
      Project p = base;
      p.morph.method = v.method;
      p.morph.interpolationBound = v.bound;
      auto rt = prepareMorph(p, dir, assets);
      if (!rt) continue;
      MorphFrameSettings fs;
      fs.resolution = res;
      const ContinuitySummary s = measureContinuity(first, last, [&](int f) {
        auto fr = evaluateMorphFrame(**rt, p.timeline.frameToSec(f), fs);
        return fr ? std::move(fr->mesh) : TriangleMesh{};
      });
      const size_t defects = continuityDefects(s.frames).size();
      std::snprintf(note, sizeof note, "at frame %d; %d^3; %zu empty frames, %zu frames over %.0f%%", s.maxVolumeFrame,
                    res, s.emptyFrames, defects, 100.0 * kMaxFrameVolumeChange);
      rows.push_back({std::string("largest volume change A..D: ") + v.name, s.maxVolumeChange, "ratio", "", note});
      std::snprintf(note, sizeof note, "%.4f m at frame %d / motion alone %.4f m", s.maxHausdorff, s.maxHausdorffFrame,
                    motionH);
      rows.push_back({std::string("largest Hausdorff A..D / motion: ") + v.name,
                      motionH > 0.0 ? s.maxHausdorff / motionH : 0.0, "ratio", "", note});
      int at = 0;
      const double inside = largestVolumeChangeWithin(s, mk.b, mk.c, at);
      std::snprintf(note, sizeof note, "at frame %d (B %d, C %d; the seams with the transitions left out)", at, mk.b,
                    mk.c);
      rows.push_back({std::string("largest volume change B..C: ") + v.name, inside, "ratio", "", note});
    }
  }
  return rows;
}

}  // namespace

ANIMORPH_BENCH("morph-continuity",
               "popping through A..D: largest frame-to-frame volume change and Hausdorff distance, old and new blend",
               benchContinuity);
