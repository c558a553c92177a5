#pragma once
// Timeline (bottom panel): transport buttons, loop, playback speed, fps and
// range fields (project edits, through commands), and a frame ruler with
// ticks and numbers that adapt to the zoom, the current-frame line, key
// ticks of the selection, and scrubbing by click or drag anywhere on it.
// Wheel over the ruler zooms around the mouse; middle-drag pans.
#include <vector>

#include "core/anim/playback.h"
#include "core/doc/document.h"
#include "ui/widgets/drag_merge.h"
#include "ui/common/layout.h"
#include "ui/common/shortcuts.h"

namespace animorph {

constexpr int kAnimorphosisMarker0 = 4;

struct TimelineState {
  double viewStartFrame = 0.0;  // visible frame span of the ruler
  double viewEndFrame = 100.0;
  bool fitToRange = true;  // follow the range until the user zooms or pans
  bool scrubbing = false;
  // Marker being dragged on the ruler: the morph's 0..3 = A..D, the animorphosis
  // interval's kAnimorphosisMarker0 + 0 (start) or + 1 (end); -1: none.
  int draggingMarker = -1;
};

// Frame spacing of the numbered ticks for a zoom level: the smallest of
// 1, 2, 5, 10, 20, 50, ... frames that puts labels at least minLabelPx apart.
int rulerLabelStep(double pixelsPerFrame, double minLabelPx = 50.0);

// Draws the panel. Transport buttons append actions (the same as the
// shortcuts); scrubbing moves the playhead directly; keyFrames are drawn as ticks.
void drawTimelinePanel(const LayoutRect& rect, Document& doc, Playback& playback, const std::vector<int>& keyFrames,
                       TimelineState& st, DragMerge& drag, std::vector<Action>& actions);

}  // namespace animorph
