#pragma once
// The stage of a baked frame as a playblast burns it in next to the frame number: for a morph
// "before A", "A..B", "B..C", "C..D" or "after D" (the markers as the bake uses them: A on B for
// a BlobTree source, D on C for a BlobTree target, scene/morph_runtime.h); "animorphosis" for a
// project whose only transformation is an animorphosis; "" for a project with neither.
#include <string>
#include <vector>

#include "core/project/project.h"

namespace animorph {

std::string frameStageLabel(const Project& p, int frame);

// Frames first..last in consecutive runs with one label each, in order.
struct FrameStageSpan {
  int first = 0, last = 0;
  std::string label;
};
std::vector<FrameStageSpan> frameStageSpans(const Project& p, int first, int last);

}  // namespace animorph
