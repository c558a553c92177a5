#include "ui/common/layout.h"

#include <algorithm>

namespace animorph {

LayoutSizes clampLayout(LayoutSizes s, glm::vec2 display, float menuBarHeight, float statusBarHeight) {
  // Horizontal: outliner + inspector + 2 splitters + viewport fit the width.
  float sideRoom = std::max(0.0f, display.x - kMinViewportPx - 2.0f * kSplitterThicknessPx);
  s.outlinerWidth = std::clamp(s.outlinerWidth, std::min(kMinPanelPx, sideRoom * 0.5f),
                               std::max(std::min(kMinPanelPx, sideRoom * 0.5f), sideRoom - kMinPanelPx));
  float inspectorMax = std::max(0.0f, sideRoom - s.outlinerWidth);
  s.inspectorWidth = std::clamp(s.inspectorWidth, std::min(kMinPanelPx, inspectorMax), inspectorMax);
  // Vertical: timeline + splitter + viewport fit between menu and status bar.
  float vertRoom = std::max(0.0f, display.y - menuBarHeight - statusBarHeight - kSplitterThicknessPx - kMinViewportPx);
  s.timelineHeight = std::clamp(s.timelineHeight, std::min(kMinTimelinePx, vertRoom), std::max(vertRoom, 0.0f));
  return s;
}

LayoutRects computeLayout(glm::vec2 display, float menuBarHeight, float statusBarHeight, LayoutSizes sizes) {
  LayoutSizes s = clampLayout(sizes, display, menuBarHeight, statusBarHeight);
  const float t = kSplitterThicknessPx;
  LayoutRects r;
  float top = menuBarHeight;
  float statusTop = display.y - statusBarHeight;
  float timelineTop = statusTop - s.timelineHeight;
  float upperHeight = std::max(0.0f, timelineTop - t - top);

  r.statusBar = {{0.0f, statusTop}, {display.x, statusBarHeight}};
  r.timeline = {{0.0f, timelineTop}, {display.x, s.timelineHeight}};
  r.timelineSplitter = {{0.0f, timelineTop - t}, {display.x, t}};
  r.outliner = {{0.0f, top}, {s.outlinerWidth, upperHeight}};
  r.outlinerSplitter = {{s.outlinerWidth, top}, {t, upperHeight}};
  float inspectorLeft = display.x - s.inspectorWidth;
  r.inspector = {{inspectorLeft, top}, {s.inspectorWidth, upperHeight}};
  r.inspectorSplitter = {{inspectorLeft - t, top}, {t, upperHeight}};
  float vpLeft = s.outlinerWidth + t;
  r.viewport = {{vpLeft, top}, {std::max(0.0f, inspectorLeft - t - vpLeft), upperHeight}};
  return r;
}

}  // namespace animorph
