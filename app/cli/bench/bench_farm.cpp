// Benchmark of a farm bake without the scheduler: the job scripts `farm slurm` writes for the demo
// (3 chunks), each array task and then the assembly run one after the other on this machine as
// Slurm would run them (bash, SLURM_ARRAY_TASK_ID set), against one `bake --gltf` of the same
// frames as the baseline. What is left per chunk is the cost of splitting: starting the process,
// loading the project, preparing the morph, and reading the chunks back. (Slurm's own scheduling
// comes on top: the test tests/cli/farm_slurm_check.py measures the whole run on a real cluster.)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/export/frame_chunks.h"
#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_demo_project.h"
#include "app/cli/bench/bench_scratch_dir.h"

namespace {

using namespace animorph;
using animorph::bench::Row;
namespace fs = std::filesystem;

// Runs a shell command quietly; its wall time in seconds, or -1 when it fails.
double runTimed(const std::string& cmd) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::system((cmd + " >/dev/null 2>&1").c_str()) != 0) return -1.0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Row> benchFarm(const bench::Options& opt) {
  const bench::DemoMorph dm = bench::loadDemoMorph();
  if (!dm.error.empty()) return {{"skipped", 0, "", "", dm.error}};
  const bench::ScratchDir scratch("animorph-bench-farm");
  if (!scratch.ok()) return {{"skipped", 0, "", "", "cannot create a temporary directory"}};
  std::error_code ec;
  const std::string exe = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) return {{"skipped", 0, "", "", "cannot find the path of this animorph-cli"}};
  const int first = dm.project.timeline.frameStart;
  const int last = opt.quick ? first + 23 : dm.project.timeline.frameEnd;
  const int chunk = (last - first) / 3 + 1;  // 3 chunks
  const std::string res = opt.quick ? "16" : "64";
  const std::string dir = scratch.path().string(), project = "'" + dm.path.string() + "'";
  const std::string frames = std::to_string(first) + ":" + std::to_string(last);

  const double single = runTimed("'" + exe + "' bake " + project + " --frames " + frames + " --res " + res +
                                 " --format none --gltf '" + dir + "/single.glb'");
  if (single < 0) return {{"skipped", 0, "", "", "bake --gltf of the demo failed"}};
  if (runTimed("'" + exe + "' farm slurm " + project + " --frames " + frames + " --chunk " + std::to_string(chunk) +
               " --res " + res + " -o '" + dir + "/farm' --format none --name demo --gltf '" + dir + "/farm.glb'") < 0)
    return {{"skipped", 0, "", "", "farm slurm failed"}};
  const size_t chunks = splitFrames(first, last, chunk).size();
  double tasks = 0.0;
  for (size_t i = 0; i < chunks; ++i) {
    const double t = runTimed("SLURM_ARRAY_TASK_ID=" + std::to_string(i) + " bash '" + dir + "/farm/slurm/demo_bake.sbatch'");
    if (t < 0) return {{"skipped", 0, "", "", "array task " + std::to_string(i) + " failed"}};
    tasks += t;
  }
  const double assemble = runTimed("bash '" + dir + "/farm/slurm/demo_assemble.sbatch'");
  if (assemble < 0) return {{"skipped", 0, "", "", "the assembly failed"}};
  char note[200];
  std::snprintf(note, sizeof note,
                "%d frames at %s^3 in %zu chunks: tasks %.2f s + assembly %.2f s, one after the other, against one "
                "bake %.2f s (baseline); Slurm's scheduling not included",
                last - first + 1, res.c_str(), chunks, tasks, assemble, single);
  return {{"overhead per chunk (no scheduler)", (tasks + assemble - single) / double(chunks), "s",
           "stated (issue 20)", note}};
}

}  // namespace

ANIMORPH_BENCH("farm", "a farm bake's job scripts run locally, task by task, against one bake (baseline)", benchFarm);
