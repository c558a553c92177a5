#include "ui/common/layout.h"

#include <algorithm>
#include <cmath>

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
  // The docked editors: between their minimum and what leaves the viewport its own.
  const float upper = std::max(0.0f, display.y - menuBarHeight - statusBarHeight - s.timelineHeight - kSplitterThicknessPx);
  const float editorsRoom = std::max(0.0f, upper - kSplitterThicknessPx - kMinViewportPx);
  s.editorsHeight = std::clamp(s.editorsHeight, std::min(kMinEditorsPx, editorsRoom), std::max(editorsRoom, 0.0f));
  s.editorsSplit = std::clamp(s.editorsSplit, kMinEditorsSplit, 1.0f - kMinEditorsSplit);
  return s;
}

namespace {

// Cuts the docked editors' area (and its splitter) off the bottom of the viewport.
void dockEditors(const LayoutSizes& s, DockedEditors docked, LayoutRects& r) {
  if (!docked.any()) return;
  const float t = kSplitterThicknessPx;
  LayoutRect& vp = r.viewport;
  const float h = std::min(s.editorsHeight, std::max(0.0f, vp.size.y - t));
  const float top = vp.max().y - h;
  r.editorsSplitter = {{vp.min.x, top - t}, {vp.size.x, t}};
  const LayoutRect area{{vp.min.x, top}, {vp.size.x, h}};
  vp.size.y = std::max(0.0f, top - t - vp.min.y);
  if (!(docked.correspondence && docked.curves)) {
    (docked.correspondence ? r.correspondence : r.curves) = area;
    return;
  }
  const float left = std::floor((area.size.x - t) * s.editorsSplit);
  r.correspondence = {area.min, {left, h}};
  r.editorsDivider = {{area.min.x + left, top}, {t, h}};
  r.curves = {{area.min.x + left + t, top}, {std::max(0.0f, area.size.x - left - t), h}};
}

}  // namespace

LayoutRects computeLayout(glm::vec2 display, float menuBarHeight, float statusBarHeight, LayoutSizes sizes,
                          DockedEditors docked) {
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
  dockEditors(s, docked, r);
  return r;
}

}  // namespace animorph
