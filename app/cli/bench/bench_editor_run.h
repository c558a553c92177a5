#pragma once
// Runs the real editor for the editor benchmarks (bench_editor.cpp, bench_statue_scrub.cpp):
// `animorph --bench FRAMES ARGS PROJECT` in a child process with private preferences, under
// xvfb-run when there is no display, and the figures it prints.
#include <filesystem>
#include <string>

namespace animorph::bench {

struct EditorRun {
  double first = -1, p50 = -1, p95 = -1, max = -1;
  double cpuSec = 0;  // CPU time of the child processes (the editor and, under xvfb-run, the X server)
  size_t frames = 0;
  // The measured frames' wall time (their sum) and the editor process's processor time over them
  // (all its threads, lavapipe's included; -1 when the editor did not print them).
  double framesWallMs = -1, framesCpuMs = -1;
  double idleSec = -1, idleCpuMsPerSec = -1;  // --idle-bench
  int idleFrames = 0;
  std::string device, output;
};

// One run of `animorph --bench FRAMES ARGS` (FRAMES 0: `animorph ARGS`) on project with preferences
// `prefsJson` (empty: defaults) in a private configuration directory; `env` is prepended; prefix
// from editorDisplayPrefix.
// Throughput of a run: the frames the window showed per second of their wall time (not 1000 / p50).
inline double framesShownPerSec(const EditorRun& r) {
  return r.framesWallMs > 0 ? 1e3 * double(r.frames) / r.framesWallMs : 0.0;
}
// The note every editor row carries: frames, wall and processor time, threads, warm.
std::string editorRunNote(const EditorRun& r);
EditorRun runEditor(const std::filesystem::path& editor, const std::filesystem::path& project,
                    const std::string& prefix, int frames, const std::string& args, const std::string& prefsJson,
                    const std::string& env = "");

// The command prefix that gives the editor a display: empty with DISPLAY set, else xvfb-run at
// 1600x900. False when there is neither.
bool editorDisplayPrefix(std::string& prefix);

// The editor next to this executable.
std::filesystem::path editorExecutable();

// The editor (editorExecutable) and the display prefix (editorDisplayPrefix) for a bench on project;
// false, with a "skipped" row added to rows, when the editor, the project or a display is missing.
template <class Rows>
bool editorBenchSetup(const std::filesystem::path& project, std::filesystem::path& editor, std::string& prefix,
                      Rows& rows) {
  editor = editorExecutable();
  if (!std::filesystem::exists(editor) || !std::filesystem::exists(project)) {
    rows.push_back({"skipped: editor or project not found", 0.0, "", "", editor.string() + ", " + project.string()});
    return false;
  }
  if (!editorDisplayPrefix(prefix)) {
    rows.push_back({"skipped: no DISPLAY and no xvfb-run", 0.0, "", "", ""});
    return false;
  }
  return true;
}

}  // namespace animorph::bench
