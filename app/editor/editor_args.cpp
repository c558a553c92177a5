#include "app/editor/editor_args.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace animorph {
namespace {

void usage() {
  std::printf(
      "usage: animorph [PROJECT.animorph | CHARACTER] [options]\n"
      "  a character (.gltf, .glb, .fbx, .dae, .obj) opens as a new untitled project with it\n"
      "  imported and framed\n"
      "  --screenshot FILE.png  render the whole editor window to FILE.png\n"
      "  --frame N              go to frame N first\n"
      "  --quit                 exit after the screenshot\n"
      "  --size WxH             window size (default 1600x900)\n"
      "  --bench N              play N frames and print frame-time figures, then exit\n"
      "  --scrub A:B            with --bench: step the current frame A..B..A, one frame per\n"
      "                         redraw, as dragging the timeline does, instead of playing\n"
      "  --scrub-hz N           with --scrub: N steps a second whatever the frame rate, as a\n"
      "                         hand does (frames between steps show the same time again)\n"
      "  --idle-bench S         leave the editor idle for S seconds after start-up, print the frames\n"
      "                         drawn and the CPU time used, then exit\n"
      "environment: ANIMORPH_GPU=name|index picks the Vulkan device; ANIMORPH_VALIDATION=1 enables\n"
      "validation (errors make the exit status non-zero); ANIMORPH_REDRAW=continuous redraws every\n"
      "frame instead of on demand (for comparison); ANIMORPH_UI_MAP=FILE writes the positions\n"
      "of named widgets to FILE (for scripted GUI tests).\n");
}

}  // namespace

bool parseEditorArgs(int argc, char** argv, EditorArgs& a) {
  for (int i = 1; i < argc; ++i) {
    std::string s = argv[i];
    auto next = [&](const char* what) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "animorph: %s needs a value\n", what);
        std::exit(2);
      }
      return argv[++i];
    };
    if (s == "--help" || s == "-h") { usage(); std::exit(0); }
    else if (s == "--version") { std::printf("animorph 0.1.0\n"); std::exit(0); }
    else if (s == "--screenshot") a.screenshot = next("--screenshot");
    else if (s == "--frame") a.frame = std::atoi(next("--frame"));
    else if (s == "--quit") a.quit = true;
    else if (s == "--bench") a.benchFrames = std::max(1, std::atoi(next("--bench")));
    else if (s == "--idle-bench") a.idleBenchSec = std::max(1.0, std::atof(next("--idle-bench")));
    else if (s == "--scrub") {
      if (std::sscanf(next("--scrub"), "%d:%d", &a.scrubFrom, &a.scrubTo) != 2 || a.scrubFrom < 0 ||
          a.scrubTo <= a.scrubFrom) {
        std::fprintf(stderr, "animorph: --scrub expects A:B with 0 <= A < B, e.g. 48:84\n");
        return false;
      }
    }
    else if (s == "--scrub-hz") {
      a.scrubHz = std::atof(next("--scrub-hz"));
      if (!(a.scrubHz > 0.0)) {
        std::fprintf(stderr, "animorph: --scrub-hz expects a positive rate, e.g. 20\n");
        return false;
      }
    }
    else if (s == "--size") {
      if (std::sscanf(next("--size"), "%dx%d", &a.width, &a.height) != 2 || a.width < 64 || a.height < 64) {
        std::fprintf(stderr, "animorph: --size expects WxH, e.g. 1600x900\n");
        return false;
      }
    } else if (!s.empty() && s[0] == '-') {
      std::fprintf(stderr, "animorph: unknown option %s (see --help)\n", s.c_str());
      return false;
    } else a.project = s;
  }
  return true;
}

}  // namespace animorph
