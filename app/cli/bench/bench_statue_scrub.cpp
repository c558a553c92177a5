// Benchmark: the real editor at 1600x900 scrubbing the statue demo (resources/demo/statue.animorph,
// docs/particles.md) through its explosion and vortex, one new frame per redraw, with the particle
// view (each particle a sphere while the time changes) and, as the baseline in the same run, with
// it off (the surface preview polygonised for every new time, the CPU worker or the GPU as Auto picks).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_editor_run.h"

namespace {

namespace fs = std::filesystem;
using animorph::bench::EditorRun;
using animorph::bench::Row;

std::vector<Row> benchStatueScrub(const animorph::bench::Options& opt) {
  std::vector<Row> rows;
  const fs::path demo = fs::path(ANIMORPH_SOURCE_DIR) / "resources/demo/statue.animorph";
  fs::path editor;
  std::string prefix;
  if (!animorph::bench::editorBenchSetup(demo, editor, prefix, rows)) return rows;
  const int frames = opt.quick ? 40 : 150;
  const struct {
    const char* name;
    const char* prefs;
  } runs[] = {{"particle view", "{\"particleView\": true}"},
              {"baseline: surface preview", "{\"particleView\": false}"}};
  // Frames 12..108 of 24 fps: 0.5..4.5 s, the explosion, the swirl and the re-forming.
  for (const auto& run : runs) {
    EditorRun r = animorph::bench::runEditor(editor, demo, prefix, frames, "--scrub 12:108", run.prefs);
    if (r.p50 <= 0) {
      rows.push_back({std::string("scrubbing the statue, ") + run.name + ": failed", 0.0, "", "", r.output.substr(0, 200)});
      continue;
    }
    const std::string n = "1600x900, frames 12..108..12; " + animorph::bench::editorRunNote(r);
    const std::string head = std::string("scrubbing the statue, ") + run.name;
    rows.push_back({head + ", frames shown per second", animorph::bench::framesShownPerSec(r), "fps",
                    run.name[0] == 'p' ? ">= 20 fps" : "", n});
    rows.push_back({head + ", frame time p50", r.p50, "ms", "", "latency of one frame, wall"});
    rows.push_back({head + ", frame time p95", r.p95, "ms", "", "latency of one frame, wall"});
    rows.push_back({std::string("scrubbing the statue, ") + run.name + ", CPU per frame", 1e3 * r.cpuSec / double(r.frames + 10),
                    "ms", "", "editor + X server, all threads, start-up included"});
  }
  return rows;
}

}  // namespace

ANIMORPH_BENCH("statue-scrub", "editor scrubbing the statue demo: particle view against the surface preview",
               benchStatueScrub);
