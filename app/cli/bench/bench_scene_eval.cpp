// Benchmark of the editor's per-frame scene evaluation of the animorphosis demo (two looping
// BlobTree creatures with thousands of keys), on the calling thread: with each tree's end
// (animationEndSec) walked at every evaluation, as the editor did before 2026-11-30, and kept per
// document revision (project/animation_end_cache.h), as the editor does now. Both in the same run,
// alternated, processor time of this thread.
#include <algorithm>
#include <ctime>
#include <filesystem>

#include "app/cli/bench/bench.h"
#include "core/project/animation_end_cache.h"
#include "core/project/project_io.h"
#include "core/scene/scene_frame.h"

namespace {

using namespace animorph;
using namespace animorph::bench;

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * double(ts.tv_sec) + 1e-6 * double(ts.tv_nsec);
}

std::vector<Row> benchSceneEval(const Options& opt) {
  namespace fs = std::filesystem;
  const fs::path demo = fs::path(ANIMORPH_SOURCE_DIR) / "resources/demo/animorphosis.animorph";
  auto project = loadProject(demo.string());
  if (!project) return {{"skipped: " + project.error(), 0.0, "", "", ""}};
  AssetCache assets;
  const std::string baseDir = demo.parent_path().string();
  const int n = opt.quick ? 40 : 400, rounds = 4;
  const uint64_t revision = 1;
  double walkedMs = 0.0, keptMs = 0.0;
  for (int r = 0; r < rounds; ++r) {  // A B A B ...
    double t0 = threadCpuMs();
    for (int i = 0; i < n; ++i) evaluateScene(*project, baseDir, assets, project->timeline.frameToSec(i % 200));
    double t1 = threadCpuMs();
    for (int i = 0; i < n; ++i) {
      AnimationEndScope ends(*project, &*project, revision);
      evaluateScene(*project, baseDir, assets, project->timeline.frameToSec(i % 200));
    }
    double t2 = threadCpuMs();
    walkedMs += t1 - t0, keptMs += t2 - t1;
  }
  const double calls = double(n) * rounds;
  const std::string note = std::to_string(int(calls)) + " evaluations each, alternated in 4 rounds; processor time of "
                           "the calling thread (latency of one evaluation), 1 thread, warm";
  return {{"scene evaluation of the animorphosis demo, tree ends walked each time", walkedMs / calls, "ms", "", note},
          {"scene evaluation of the animorphosis demo, tree ends kept per revision", keptMs / calls, "ms", "", note},
          {"walked / kept", walkedMs / std::max(1e-9, keptMs), "ratio", "", ""}};
}

}  // namespace

ANIMORPH_BENCH("scene-eval", "per-frame scene evaluation of the animorphosis demo: tree ends walked vs kept",
               benchSceneEval);
