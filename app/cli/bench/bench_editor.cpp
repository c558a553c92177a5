// Benchmark: the real editor at 1600x900 with the demo character playing
// (frame time p50/p95, start to first frame) and scrubbing the morph's implicit
// stage (fps with Auto's choice of preview device and with the CPU worker), and the CPU an idle editor
// uses (on-demand redraw against continuous). Runs `animorph --bench` / `--idle-bench`
// in child processes, under xvfb-run when there is no display.
#include <sys/resource.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/bench/bench.h"

namespace {

namespace fs = std::filesystem;

std::string runCapture(const std::string& cmd) {
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  std::array<char, 512> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) out += buf.data();
  ::pclose(p);
  return out;
}

// One run of `animorph --bench FRAMES ARGS` (FRAMES 0: `animorph ARGS`) on the demo with preferences
// `prefsJson` (empty: defaults) in a private configuration directory; `env` is prepended.
struct EditorRun {
  double first = -1, p50 = -1, p95 = -1, max = -1;
  double cpuSec = 0;  // CPU time of the child processes (the editor and, under xvfb-run, the X server)
  size_t frames = 0;
  double idleSec = -1, idleCpuMsPerSec = -1;  // --idle-bench
  int idleFrames = 0;
  std::string device, output;
};

EditorRun runEditor(const fs::path& editor, const fs::path& demo, const std::string& prefix, int frames,
                    const std::string& args, const std::string& prefsJson, const std::string& env = "") {
  EditorRun r;
  std::error_code ec;
  const fs::path cfg = fs::temp_directory_path() / ("animorph-bench-editor-" + std::to_string(::getpid()));
  fs::create_directories(cfg / "animorph", ec);
  if (!prefsJson.empty())
    if (FILE* f = std::fopen((cfg / "animorph" / "prefs.json").c_str(), "w")) {
      std::fputs(prefsJson.c_str(), f);
      std::fclose(f);
    }
  const std::string bench = frames > 0 ? " --bench " + std::to_string(frames) : std::string();
  const std::string cmd = "XDG_CONFIG_HOME='" + cfg.string() + "' " + env + " " + prefix + "'" + editor.string() +
                          "' --size 1600x900" + bench + " " + args + " '" + demo.string() + "' 2>&1";
  auto childCpu = [] {
    rusage u{};
    getrusage(RUSAGE_CHILDREN, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  const double cpu0 = childCpu();
  r.output = runCapture(cmd);
  r.cpuSec = childCpu() - cpu0;
  fs::remove_all(cfg, ec);
  const std::string& out = r.output;
  if (auto pos = out.find("start to first frame:"); pos != std::string::npos)
    std::sscanf(out.c_str() + pos, "start to first frame: %lf ms", &r.first);
  char device[256] = {0};
  if (auto pos = out.find("frame time over"); pos != std::string::npos)
    std::sscanf(out.c_str() + pos, "frame time over %zu frames: p50 %lf ms, p95 %lf ms, max %lf ms (device: %255[^)])",
                &r.frames, &r.p50, &r.p95, &r.max, device);
  r.device = device;
  if (auto pos = out.find("idle over"); pos != std::string::npos)
    std::sscanf(out.c_str() + pos, "idle over %lf s: %d frames, CPU %lf ms per second", &r.idleSec, &r.idleFrames,
                &r.idleCpuMsPerSec);
  return r;
}

std::vector<animorph::bench::Row> benchEditor(const animorph::bench::Options& opt) {
  std::vector<animorph::bench::Row> rows;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path editor = self.parent_path() / "animorph";
  // The demo project lives in the source tree: ANIMORPH_DEMO overrides.
  const char* demoEnv = std::getenv("ANIMORPH_DEMO");
  fs::path demo = demoEnv ? fs::path(demoEnv) : fs::path(ANIMORPH_SOURCE_DIR) / "resources/demo/demo.animorph";
  if (!fs::exists(editor) || !fs::exists(demo)) {
    rows.push_back({"skipped: editor or demo project not found", 0.0, "", "", editor.string()});
    return rows;
  }
  std::string prefix;
  if (!std::getenv("DISPLAY")) {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) {
      rows.push_back({"skipped: no DISPLAY and no xvfb-run", 0.0, "", "", ""});
      return rows;
    }
    prefix = "xvfb-run -a -s '-screen 0 1600x900x24' ";
  }
  const int frames = opt.quick ? 60 : 300;
  EditorRun play = runEditor(editor, demo, prefix, frames, "", "");
  if (play.first < 0 || play.p95 < 0) {
    rows.push_back({"failed: the editor printed no figures", 0.0, "", "", play.output.substr(0, 200)});
    return rows;
  }
  const std::string note = std::to_string(play.frames) + " frames, 1600x900, demo playing, " + play.device;
  rows.push_back({"start to first frame", play.first, "ms", "<= 1500 ms", ""});
  rows.push_back({"frame time p50", play.p50, "ms", "", note});
  rows.push_back({"frame time p95", play.p95, "ms", "<= 10 ms", note});
  rows.push_back({"frame time max", play.max, "ms", "", ""});
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
    const std::string n = std::to_string(r.frames) + " frames, 1600x900, frames 50..82..50, preview at 96^3";
    rows.push_back({std::string("scrubbing the morph, ") + sc.name + ", fps at p50", 1000.0 / r.p50, "fps", ">= 30 fps", n});
    rows.push_back({std::string("scrubbing the morph, ") + sc.name + ", frame time p95", r.p95, "ms", "", ""});
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
