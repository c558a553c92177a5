#pragma once
// The editor's fixed layout (no docking): menu bar on top, outliner left,
// inspector right, timeline below them, status bar at the very bottom and
// the 3D viewport in the centre. Pure geometry, in window pixels.
#include <glm/glm.hpp>

namespace animorph {

struct LayoutRect {
  glm::vec2 min{0.0f};
  glm::vec2 size{0.0f};
  glm::vec2 max() const { return min + size; }
};

// User-resizable sizes (the splitters move them; saved in preferences).
struct LayoutSizes {
  float outlinerWidth = 260.0f;
  float inspectorWidth = 320.0f;
  float timelineHeight = 140.0f;
};

struct LayoutRects {
  LayoutRect outliner, inspector, timeline, statusBar, viewport;
  LayoutRect outlinerSplitter, inspectorSplitter, timelineSplitter;  // thin drag handles
};

inline constexpr float kSplitterThicknessPx = 6.0f;
inline constexpr float kMinPanelPx = 120.0f;     // narrowest side panel
inline constexpr float kMinTimelinePx = 80.0f;   // lowest timeline
inline constexpr float kMinViewportPx = 120.0f;  // the viewport never disappears

// Clamps sizes so every panel keeps its minimum and the viewport keeps at
// least kMinViewportPx in both directions (when the window is large enough).
LayoutSizes clampLayout(LayoutSizes s, glm::vec2 display, float menuBarHeight, float statusBarHeight);

// Rectangles for a window of size display. sizes are clamped first.
LayoutRects computeLayout(glm::vec2 display, float menuBarHeight, float statusBarHeight, LayoutSizes sizes);

}  // namespace animorph
