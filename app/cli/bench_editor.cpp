// Benchmark: the real editor at 1600x900 with the demo character playing
// (frame time p50/p95, start to first frame). Runs `animorph --bench` in a
// child process, under xvfb-run when there is no display.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/bench.h"

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
  const std::string cfg = (fs::temp_directory_path() / ("animorph-bench-editor-" + std::to_string(::getpid()))).string();
  const std::string cmd = "XDG_CONFIG_HOME='" + cfg + "' " + prefix + "'" + editor.string() + "' --size 1600x900 --bench " +
                          std::to_string(frames) + " '" + demo.string() + "' 2>&1";
  const std::string out = runCapture(cmd);
  fs::remove_all(cfg, ec);
  double first = -1, p50 = -1, p95 = -1, mx = -1;
  size_t n = 0;
  char device[256] = {0};
  if (auto pos = out.find("start to first frame:"); pos != std::string::npos)
    std::sscanf(out.c_str() + pos, "start to first frame: %lf ms", &first);
  if (auto pos = out.find("frame time over"); pos != std::string::npos)
    std::sscanf(out.c_str() + pos, "frame time over %zu frames: p50 %lf ms, p95 %lf ms, max %lf ms (device: %255[^)])", &n,
                &p50, &p95, &mx, device);
  if (first < 0 || p95 < 0) {
    rows.push_back({"failed: the editor printed no figures", 0.0, "", "", out.substr(0, 200)});
    return rows;
  }
  const std::string note = std::to_string(n) + " frames, 1600x900, demo playing, " + device;
  rows.push_back({"start to first frame", first, "ms", "<= 1500 ms", ""});
  rows.push_back({"frame time p50", p50, "ms", "", note});
  rows.push_back({"frame time p95", p95, "ms", "<= 10 ms", note});
  rows.push_back({"frame time max", mx, "ms", "", ""});
  return rows;
}

}  // namespace

ANIMORPH_BENCH("editor", "editor frame time and start-up with the demo playing (real window)", benchEditor);
