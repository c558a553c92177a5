#pragma once
// The last settings of File > Export > Playblast... (saved in the project, changed through a
// command like any other project setting): which frames, the picture size, whether the frame
// number and the morph's stage are burned in, which camera, and the .mp4 to write.
#include <string>

namespace animorph {

struct PlayblastSettings {
  // Frames first..last (inclusive). useTimeline: the timeline's range instead (the default).
  bool useTimeline = true;
  int first = 0, last = 96;
  int resolution = 48;            // polygonisation cells of the implicit frames (2..1024)
  int width = 1280, height = 720;  // pixels, even (H.264), 16..8192
  bool burnIn = true;             // frame number and stage (A..B, B..C, ...) in the top-left corner
  // The editor's viewport camera as it is when the playblast starts (a playblast shows what the
  // animator looks at); false, or where there is no viewport (bake --mp4): one camera framing
  // every frame of the range.
  bool viewportCamera = true;
  std::string output;             // the .mp4; empty: not chosen yet
  bool operator==(const PlayblastSettings&) const = default;
};

// The settings' problem ("" when none): picture size odd or out of range, resolution out of range.
std::string playblastSizeProblem(const PlayblastSettings& s);

}  // namespace animorph
