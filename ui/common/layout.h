#pragma once
// The editor's fixed layout: menu bar on top, outliner left, inspector right,
// timeline below them, status bar at the very bottom and the 3D viewport in
// the centre. The tool editors (correspondence, curves) dock in an area below
// the viewport while open, side by side when both are, so the viewport stays
// in view while an artist links nodes and shapes curves. Pure geometry, in
// window pixels.
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
  float editorsHeight = 340.0f;  // the docked tool editors' area
  float editorsSplit = 0.5f;     // the correspondence editor's share of the area's width when both are open
};

// Which tool editors are open (docked below the viewport).
struct DockedEditors {
  bool correspondence = false;
  bool curves = false;
  bool any() const { return correspondence || curves; }
};

struct LayoutRects {
  LayoutRect outliner, inspector, timeline, statusBar, viewport;
  LayoutRect outlinerSplitter, inspectorSplitter, timelineSplitter;  // thin drag handles
  // The docked tool editors (empty when closed), the handle above their area and the one between them.
  LayoutRect correspondence, curves;
  LayoutRect editorsSplitter, editorsDivider;
};

inline constexpr float kSplitterThicknessPx = 6.0f;
inline constexpr float kMinPanelPx = 120.0f;     // narrowest side panel
inline constexpr float kMinTimelinePx = 80.0f;   // lowest timeline
inline constexpr float kMinViewportPx = 120.0f;  // the viewport never disappears
inline constexpr float kMinEditorsPx = 140.0f;   // lowest docked editor area
inline constexpr float kMinEditorsSplit = 0.2f;  // narrowest share of either docked editor

// Clamps sizes so every panel keeps its minimum and the viewport keeps at
// least kMinViewportPx in both directions (when the window is large enough),
// also above the docked editors' area; editorsSplit stays in
// [kMinEditorsSplit, 1 - kMinEditorsSplit].
LayoutSizes clampLayout(LayoutSizes s, glm::vec2 display, float menuBarHeight, float statusBarHeight);

// Rectangles for a window of size display. sizes are clamped first. With
// docked editors the viewport ends above their area (and its splitter); with
// both, the correspondence editor takes editorsSplit of the width on the left.
LayoutRects computeLayout(glm::vec2 display, float menuBarHeight, float statusBarHeight, LayoutSizes sizes,
                          DockedEditors docked = {});

}  // namespace animorph
