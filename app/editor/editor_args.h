#pragma once
// The editor's command line (animorph --help).
#include <string>

namespace animorph {

struct EditorArgs {
  std::string project;
  std::string screenshot;
  int frame = -1;
  bool quit = false;
  int width = 1600, height = 900;
  int benchFrames = 0;
  int scrubFrom = -1, scrubTo = -1;  // --scrub A:B: the bench steps the current frame A..B..A instead of playing
  double scrubHz = 0.0;               // --scrub-hz N: N steps a second of wall time (0: one per redraw)
  double idleBenchSec = 0.0;          // --idle-bench S: measure S seconds without input, then exit
};

// Parses argv into a; prints usage and exits for --help/--version. Returns false (after a message on
// stderr) on a bad option or value.
bool parseEditorArgs(int argc, char** argv, EditorArgs& a);

}  // namespace animorph
