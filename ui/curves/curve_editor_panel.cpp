#include "ui/curves/curve_editor_panel.h"

#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "ui/curves/curve_editor_intern.h"
#include "ui/curves/curve_source.h"
#include "ui/widgets/tool_window.h"
#include "ui/widgets/view_zoom.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

void frameAll(CurveEditorState& st, const CurveSource& src, const std::vector<CurveChannel>& channels,
              const CurveAxis& ax) {
  double f0 = 1e300, f1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const auto& c : channels) {
    if (hiddenChannel(st, c)) continue;
    ConstTrackPtr tp = src.track(c.addr);
    for (int k = 0, n = keyCount(tp); k < n; ++k) {
      double t = 0.0;
      ParamSample v;
      if (!keyAt(tp, k, t, v)) continue;
      f0 = std::min(f0, t * ax.xPerTime);
      f1 = std::max(f1, t * ax.xPerTime);
    }
  }
  if (f0 > f1) {
    f0 = ax.rangeStart;
    f1 = ax.rangeEnd;
  }
  if (f1 - f0 < 2.0 * ax.snapStep) {
    f0 -= ax.snapStep;
    f1 += ax.snapStep;
  }
  // Values: sample the curves over the key range (overshoot between keys counts).
  for (const auto& c : channels) {
    if (hiddenChannel(st, c)) continue;
    ConstTrackPtr tp = src.track(c.addr);
    for (int i = 0; i <= 200; ++i) {
      ParamSample v;
      if (!sampleTrack(tp, (f0 + (f1 - f0) * i / 200.0) / ax.xPerTime, v)) break;
      double x = channelOf(v, c.channel);
      v0 = std::min(v0, x);
      v1 = std::max(v1, x);
    }
  }
  if (v0 > v1) {
    v0 = -1.0;
    v1 = 1.0;
  }
  if (v1 - v0 < 1e-3) {
    v0 -= 0.5;
    v1 += 0.5;
  }
  double fp = (f1 - f0) * 0.06, vp = (v1 - v0) * 0.12;
  st.frame0 = f0 - fp;
  st.frame1 = f1 + fp;
  st.value0 = v0 - vp;
  st.value1 = v1 + vp;
}

// The graph's widget (it takes the rest of the window): its rectangle, hover and activity, the
// framing (F, Frame all, a new source), then zoom (wheel: x, Ctrl+wheel: values) around the mouse
// and middle-drag panning.
void placeAndNavigateGraph(CurveFrame& f, bool frameAllNow) {
  CurveEditorState& st = f.st;
  ImGuiIO& io = ImGui::GetIO();
  ImVec2 avail = ImGui::GetContentRegionAvail();
  avail.x = std::max(avail.x, 50.0f);
  avail.y = std::max(avail.y, 50.0f);
  f.avail = avail;
  f.g0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##graph", avail,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle |
                             ImGuiButtonFlags_MouseButtonRight);
  noteWidget("curve/graph");
  f.hovered = ImGui::IsItemHovered();
  f.active = ImGui::IsItemActive();
  st.graphMin = {f.g0.x, f.g0.y};
  st.graphMax = {f.g0.x + avail.x, f.g0.y + avail.y};
  if (st.frameAllNext || frameAllNow || (st.focused && !io.WantTextInput && ImGui::IsKeyPressed('F', false) &&
                                         !io.KeyCtrl && !io.KeyAlt)) {
    frameAll(st, f.src, f.channels, f.ax);
    st.frameAllNext = false;
  }
  f.mouse = glm::vec2(io.MousePos.x, io.MousePos.y);
  if (f.hovered && io.MouseWheel != 0.0f) {
    glm::dvec2 pivot = pixelToCurve(st, f.mouse);
    if (io.KeyCtrl)
      scaleSpanAround(st.value0, st.value1, pivot.y, wheelSpanFactor(io.MouseWheel));
    else
      scaleSpanAround(st.frame0, st.frame1, pivot.x, wheelSpanFactor(io.MouseWheel));
  }
  if (f.active && ImGui::IsMouseDown(ImGuiMouseButton_Middle) && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    panSpan(st.frame0, st.frame1, io.MouseDelta.x, avail.x);
    panSpan(st.value0, st.value1, io.MouseDelta.y, avail.y, /*contentUp=*/true);
  }
}

// The source to show: the animorphosis' s curves while the correspondence editor asks for them,
// else the selection's. A new source resets the selection, the framing and any drag.
std::unique_ptr<CurveSource> curveSourceFor(Document& doc, CurveEditorState& st) {
  std::unique_ptr<CurveSource> source =
      st.animorphosis ? makeAnimorphosisCurveSource(doc, st.animorphosisLinkA, st.animorphosisLinkB) : nullptr;
  if (!source) source = curveSourceForSelection(doc);
  if (source && st.sourceId != source->id()) {
    st.sourceId = source->id();
    st.selection.clear();
    st.frameAllNext = true;
    st.drag = CurveEditorState::Drag::None;
  }
  return source;
}

}  // namespace

glm::vec2 curveToPixel(const CurveEditorState& st, double frame, double value) {
  glm::vec2 size = st.graphMax - st.graphMin;
  double x = st.graphMin.x + (frame - st.frame0) / (st.frame1 - st.frame0) * size.x;
  double y = st.graphMax.y - (value - st.value0) / (st.value1 - st.value0) * size.y;
  return {float(x), float(y)};
}

glm::dvec2 pixelToCurve(const CurveEditorState& st, glm::vec2 px) {
  glm::vec2 size = st.graphMax - st.graphMin;
  double f = st.frame0 + (px.x - st.graphMin.x) / std::max(1.0f, size.x) * (st.frame1 - st.frame0);
  double v = st.value0 + (st.graphMax.y - px.y) / std::max(1.0f, size.y) * (st.value1 - st.value0);
  return {f, v};
}

void drawCurveEditorPanel(const LayoutRect& area, Document& doc, CurveEditorState& st, StatusMessage& status) {
  if (!beginDockedToolWindow("Curve Editor", ImVec2(area.min.x, area.min.y), ImVec2(area.size.x, area.size.y),
                             "curve/window", {st.visible, st.placeNext, st.focused}))
    return;
  std::unique_ptr<CurveSource> source = curveSourceFor(doc, st);
  if (!source) {
    ImGui::TextDisabled("Select a node of a BlobTree actor, or the morph (nothing selected), to see its curves.");
    ImGui::End();
    return;
  }
  CurveFrame f{doc, st, status, *source, source->axis(), source->channels(), "curve/" + source->id()};
  pruneCurveSelection(f);
  const bool frameAllNow = drawCurveToolbar(f);
  drawCurveChannelList(f);
  ImGui::SameLine();
  placeAndNavigateGraph(f, frameAllNow);
  collectCurveKeys(f);
  // Mouse: press (a new key, else picking), drag, release; then the keyboard and the key menu.
  if (!addCurveKeyOnClick(f) && f.hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) pressOnCurveGraph(f);
  if (f.hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) rightClickCurveKey(f);
  dragCurveKeys(f);
  releaseCurveDrag(f);
  curveKeyShortcuts(f);
  drawCurveKeyMenu(f);
  drawCurveGraph(f);
  ImGui::End();
}

}  // namespace animorph
