#include "app/cli/bench/bench_editor_run.h"

#include <sys/resource.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>

namespace animorph::bench {

namespace fs = std::filesystem;

namespace {

std::string runCapture(const std::string& cmd) {
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  std::array<char, 512> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) out += buf.data();
  ::pclose(p);
  return out;
}

}  // namespace

EditorRun runEditor(const fs::path& editor, const fs::path& demo, const std::string& prefix, int frames,
                    const std::string& args, const std::string& prefsJson, const std::string& env) {
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
  if (auto pos = out.find("frames shown:"); pos != std::string::npos) {
    size_t shown = 0;
    std::sscanf(out.c_str() + pos, "frames shown: %zu in %lf ms wall, %lf ms processor", &shown, &r.framesWallMs,
                &r.framesCpuMs);
  }
  if (auto pos = out.find("idle over"); pos != std::string::npos)
    std::sscanf(out.c_str() + pos, "idle over %lf s: %d frames, CPU %lf ms per second", &r.idleSec, &r.idleFrames,
                &r.idleCpuMsPerSec);
  return r;
}

std::string editorRunNote(const EditorRun& r) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%zu frames, warm (after 10 start-up frames): %.0f ms wall, %.0f ms processor (the editor process's "
                "threads: UI, previews, the Vulkan driver's -- lavapipe runs one per core; %ld cores), %s",
                r.frames, r.framesWallMs, r.framesCpuMs, ::sysconf(_SC_NPROCESSORS_ONLN), r.device.c_str());
  return buf;
}

bool editorDisplayPrefix(std::string& prefix) {
  prefix.clear();
  if (std::getenv("DISPLAY")) return true;
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) return false;
  prefix = "xvfb-run -a -s '-screen 0 1600x900x24' ";
  return true;
}

fs::path editorExecutable() {
  std::error_code ec;
  return fs::read_symlink("/proc/self/exe", ec).parent_path() / "animorph";
}

}  // namespace animorph::bench
