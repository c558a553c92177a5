// Benchmark: the real editor at 1600x900 with the demo character playing
// (frame time p50/p95, start to first frame) and scrubbing the morph's implicit
// stage (fps with Auto's choice of preview device and with the CPU worker), and the CPU an idle editor
// uses (on-demand redraw against continuous). Runs `animorph --bench` / `--idle-bench`
// in child processes, under xvfb-run when there is no display.
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_editor_run.h"

namespace {

namespace fs = std::filesystem;
using animorph::bench::EditorRun;
using animorph::bench::runEditor;

std::vector<animorph::bench::Row> benchEditor(const animorph::bench::Options& opt) {
  std::vector<animorph::bench::Row> rows;
  // The demo project lives in the source tree: ANIMORPH_DEMO overrides.
  const char* demoEnv = std::getenv("ANIMORPH_DEMO");
  fs::path demo = demoEnv ? fs::path(demoEnv) : fs::path(ANIMORPH_SOURCE_DIR) / "resources/demo/demo.animorph";
  fs::path editor;
  std::string prefix;
  if (!animorph::bench::editorBenchSetup(demo, editor, prefix, rows)) return rows;
  const int frames = opt.quick ? 60 : 300;
  EditorRun play = runEditor(editor, demo, prefix, frames, "", "");
  if (play.first < 0 || play.p95 < 0) {
    rows.push_back({"failed: the editor printed no figures", 0.0, "", "", play.output.substr(0, 200)});
    return rows;
  }
  const std::string note = "1600x900, demo playing; " + animorph::bench::editorRunNote(play);
  rows.push_back({"start to first frame", play.first, "ms", "<= 1500 ms", ""});
  rows.push_back({"frame time p50", play.p50, "ms", "", note});
  rows.push_back({"frame time p95", play.p95, "ms", "<= 10 ms", note});
  rows.push_back({"frame time max", play.max, "ms", "", ""});
  rows.push_back({"frames shown per second, demo playing", animorph::bench::framesShownPerSec(play), "fps", "", note});
  // Scrubbing the morph's implicit stage (B..C of the demo: frames 48..84), one new frame per
  // redraw, with the device Auto picks (the GPU path for this morph of convolution stand-ins, on
  // CPU devices too) and with the CPU worker forced, for comparison.
  const struct {
    const char* name;
    const char* prefs;
    const char* args;
  } scrubs[] = {{"Auto preview", "", "--scrub 50:82"},
                {"CPU worker preview", "{\"previewDevice\": \"cpu\"}", "--scrub 50:82"},
                // As a hand drags: 20 steps a second whatever the frame rate, so some frames show the
                // same time again (before 2026-11-22 each such pause started a refine on the GPU path).
                {"Auto preview, 20 steps/s", "", "--scrub 50:82 --scrub-hz 20"}};
  for (const auto& sc : scrubs) {
    EditorRun r = runEditor(editor, demo, prefix, opt.quick ? 40 : 150, sc.args, sc.prefs);
    if (r.p50 <= 0) {
      rows.push_back({std::string("scrubbing, ") + sc.name + ": failed", 0.0, "", "", r.output.substr(0, 200)});
      continue;
    }
    const std::string n = "1600x900, frames 50..82..50, preview at 96^3; " + animorph::bench::editorRunNote(r);
    const std::string head = std::string("scrubbing the morph, ") + sc.name;
    rows.push_back({head + ", frames shown per second", animorph::bench::framesShownPerSec(r), "fps", ">= 30 fps", n});
    rows.push_back({head + ", frame time p50", r.p50, "ms", "", "latency of one frame, wall"});
    rows.push_back({head + ", frame time p95", r.p95, "ms", "", "latency of one frame, wall"});
    if (r.framesCpuMs >= 0)
      rows.push_back({head + ", editor processor time per frame", r.framesCpuMs / double(std::max<size_t>(1, r.frames)),
                      "ms", "", "the measured frames only, editor process, all threads"});
    // Less load-dependent than the frame times: CPU of the whole run (start-up included) per frame.
    rows.push_back({std::string("scrubbing the morph, ") + sc.name + ", CPU per frame", 1e3 * r.cpuSec / double(r.frames + 10),
                    "ms", "", "editor + X server, all threads, start-up included; 2 cores give 2 ms per ms"});
  }
  // The editor left alone: it draws on demand (a frame a second, and on input), against the same
  // editor redrawing every frame (ANIMORPH_REDRAW=continuous), measured in the same run.
  const std::string idleArgs = std::string("--idle-bench ") + (opt.quick ? "3" : "6");
  EditorRun idle = runEditor(editor, demo, prefix, 0, idleArgs, "");
  EditorRun busy = runEditor(editor, demo, prefix, 0, idleArgs, "", "ANIMORPH_REDRAW=continuous");
  if (idle.idleSec <= 0 || busy.idleSec <= 0) {
    rows.push_back({"idle editor: failed", 0.0, "", "", (idle.idleSec <= 0 ? idle : busy).output.substr(0, 200)});
    return rows;
  }
  auto idleNote = [](const EditorRun& r) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%d frames in %.1f s, editor process, all threads", r.idleFrames, r.idleSec);
    return std::string(buf);
  };
  rows.push_back({"idle editor, CPU per second (on demand)", idle.idleCpuMsPerSec, "ms/s", "", idleNote(idle)});
  rows.push_back({"idle editor, CPU per second (continuous redraw)", busy.idleCpuMsPerSec, "ms/s", "", idleNote(busy)});
  rows.push_back({"idle editor, continuous / on demand", busy.idleCpuMsPerSec / std::max(1e-3, idle.idleCpuMsPerSec),
                  "ratio", "", "CPU the on-demand redraw saves while nothing changes"});
  return rows;
}

}  // namespace

ANIMORPH_BENCH("editor", "editor frame time and start-up with the demo playing (real window)", benchEditor);
