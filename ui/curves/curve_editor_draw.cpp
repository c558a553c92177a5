// The curve editor's drawing: the toolbar, the channel list and the graph (grid, curves,
// playheads, keys, handles, the selection box) (curve_editor_intern.h).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "ui/curves/curve_editor_intern.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

ImU32 channelColor(int index) {
  static const ImU32 kPalette[6] = {IM_COL32(240, 90, 90, 255),  IM_COL32(110, 215, 100, 255),
                                    IM_COL32(100, 150, 255, 255), IM_COL32(215, 120, 235, 255),
                                    IM_COL32(90, 215, 215, 255),  IM_COL32(235, 235, 240, 255)};
  if (index < 0 || index > 5) return IM_COL32(235, 200, 90, 255);
  return kPalette[index];
}

// Grid line spacing: 1, 2, 5 x 10^k with at least minPx between lines.
double niceStep(double unitsPerPx, double minPx) {
  double raw = unitsPerPx * minPx;
  double p = std::pow(10.0, std::floor(std::log10(std::max(raw, 1e-12))));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

// The background, the range (playback range, or u in [0, 1]) in a lighter tone, the grid with
// labels (x along the bottom, values along the left) and the axis' name bottom right.
void drawGraphGrid(const CurveFrame& f, ImDrawList* dl) {
  const CurveEditorState& st = f.st;
  const ImVec2 g0 = f.g0, g1(st.graphMax.x, st.graphMax.y);
  dl->AddRectFilled(g0, g1, IM_COL32(30, 30, 34, 255));
  float rx0 = curveToPixel(st, f.ax.rangeStart, 0.0).x, rx1 = curveToPixel(st, f.ax.rangeEnd, 0.0).x;
  dl->AddRectFilled(ImVec2(std::max(g0.x, rx0), g0.y), ImVec2(std::min(g1.x, rx1), g1.y), IM_COL32(38, 38, 44, 255));
  char buf[32];
  const float lineH = ImGui::GetTextLineHeight();
  double fStep = niceStep((st.frame1 - st.frame0) / f.avail.x, 60.0);
  if (f.ax.xPerTime != 1.0) fStep = std::max(1.0, fStep);  // whole frames
  for (double x = std::ceil(st.frame0 / fStep) * fStep; x <= st.frame1; x += fStep) {
    float px = curveToPixel(st, x, 0.0).x;
    dl->AddLine(ImVec2(px, g0.y), ImVec2(px, g1.y), IM_COL32(55, 55, 62, 255));
    std::snprintf(buf, sizeof buf, "%g", std::abs(x) < fStep * 1e-6 ? 0.0 : x);  // never "-0"
    dl->AddText(ImVec2(px + 3.0f, g1.y - lineH - 2.0f), IM_COL32(150, 150, 160, 255), buf);
  }
  double vStep = niceStep((st.value1 - st.value0) / f.avail.y, 40.0);
  for (double v = std::ceil(st.value0 / vStep) * vStep; v <= st.value1; v += vStep) {
    float y = curveToPixel(st, 0.0, v).y;
    bool zero = std::abs(v) < vStep * 1e-3;
    dl->AddLine(ImVec2(g0.x, y), ImVec2(g1.x, y), zero ? IM_COL32(85, 85, 95, 255) : IM_COL32(55, 55, 62, 255));
    std::snprintf(buf, sizeof buf, "%g", zero ? 0.0 : v);
    dl->AddText(ImVec2(g0.x + 3.0f, y - lineH), IM_COL32(150, 150, 160, 255), buf);
  }
  ImVec2 sz = ImGui::CalcTextSize(f.ax.label.c_str());
  dl->AddText(ImVec2(g1.x - sz.x - 6.0f, g1.y - 2.0f * lineH - 4.0f), IM_COL32(170, 170, 185, 255),
              f.ax.label.c_str());
}

// The visible curves, sampled every 2 pixels.
void drawCurves(const CurveFrame& f, ImDrawList* dl) {
  const CurveEditorState& st = f.st;
  const ImVec2 g0 = f.g0, g1(st.graphMax.x, st.graphMax.y);
  for (const auto& c : f.channels) {
    if (hiddenChannel(st, c)) continue;
    ConstTrackPtr tp = f.src.track(c.addr);
    std::vector<ImVec2> pts;
    for (float x = g0.x; x <= g1.x + 2.0f; x += 2.0f) {
      double fx = pixelToCurve(st, {x, 0.0f}).x;
      ParamSample v;
      if (!sampleTrack(tp, fx / f.ax.xPerTime, v)) break;
      glm::vec2 p = curveToPixel(st, fx, channelOf(v, c.channel));
      pts.push_back(ImVec2(p.x, std::clamp(p.y, g0.y - 1000.0f, g1.y + 1000.0f)));
    }
    if (pts.size() >= 2) dl->AddPolyline(pts.data(), int(pts.size()), channelColor(c.colorIndex), 0, 1.5f);
  }
}

// Playheads: the current frame (or its progress u).
void drawPlayheads(const CurveFrame& f, ImDrawList* dl) {
  const float top = f.g0.y, bottom = f.st.graphMax.y;
  const float lineH = ImGui::GetTextLineHeight();
  char buf[32];
  for (const CurvePlayhead& ph : f.ax.playheads) {
    const ImU32 col = ph.secondary ? IM_COL32(240, 160, 70, 255) : IM_COL32(90, 160, 255, 255);
    float cx = curveToPixel(f.st, ph.x, 0.0).x;
    dl->AddLine(ImVec2(cx, top), ImVec2(cx, bottom), col, 2.0f);
    if (!ph.label.empty()) {
      std::snprintf(buf, sizeof buf, "%.2f", ph.x);
      dl->AddText(ImVec2(cx + 4.0f, top + 2.0f + (ph.secondary ? lineH : 0.0f)), col, (ph.label + " " + buf).c_str());
    }
  }
}

// Keys (shaped by interpolation: square constant, triangle linear, circle Hermite) and the handles
// of selected ones.
void drawKeys(const CurveFrame& f, ImDrawList* dl) {
  for (const auto& k : f.keys) {
    bool sel = f.st.selection.count(k.ref) > 0;
    if (showsHandles(f, k)) {
      glm::vec2 d = handleDir(f, k.ref);
      for (int side : {-1, 1}) {
        glm::vec2 h = k.px + float(side) * d;
        dl->AddLine(ImVec2(k.px.x, k.px.y), ImVec2(h.x, h.y), IM_COL32(200, 200, 210, 200), 1.0f);
        dl->AddCircleFilled(ImVec2(h.x, h.y), 3.5f, IM_COL32(220, 220, 230, 255));
      }
    }
    float r = 4.0f;
    ImU32 fill = sel ? IM_COL32(255, 200, 60, 255) : IM_COL32(20, 20, 24, 255);
    if (k.interp == KeyInterp::Constant)
      dl->AddRectFilled(ImVec2(k.px.x - r, k.px.y - r), ImVec2(k.px.x + r, k.px.y + r), fill);
    else if (k.interp == KeyInterp::Linear)
      dl->AddTriangleFilled(ImVec2(k.px.x, k.px.y - r - 1.0f), ImVec2(k.px.x + r + 1.0f, k.px.y + r),
                            ImVec2(k.px.x - r - 1.0f, k.px.y + r), fill);
    else
      dl->AddCircleFilled(ImVec2(k.px.x, k.px.y), r, fill);
    dl->AddCircle(ImVec2(k.px.x, k.px.y), r + 1.0f, IM_COL32(235, 235, 240, 255), 12, 1.0f);
  }
}

}  // namespace

bool drawCurveToolbar(CurveFrame& f) {
  CurveEditorState& st = f.st;
  const std::vector<KeyRef> selKeys = selectedKeys(st);
  const bool haveSel = !selKeys.empty();
  auto interpButton = [&](const char* label, KeyInterp mode, const char* key) {
    if (ImGui::Button(label) && haveSel) setKeysInterp(f, selKeys, mode);
    noteWidget(std::string("curve/") + key);
    ImGui::SameLine();
  };
  ImGui::BeginDisabled(!haveSel);
  interpButton("Constant", KeyInterp::Constant, "constant");
  interpButton("Linear", KeyInterp::Linear, "linear");
  interpButton("Hermite", KeyInterp::Hermite, "hermite");
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  if (ImGui::Button("Auto tangents")) setKeysTangentMode(f, selKeys, false);
  noteWidget("curve/auto_tangents");
  ImGui::SameLine();
  if (ImGui::Button("User tangents")) setKeysTangentMode(f, selKeys, true);
  noteWidget("curve/user_tangents");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  bool frameAllNow = ImGui::Button("Frame all (F)");
  noteWidget("curve/frame_all");
  ImGui::SameLine();
  ImGui::Checkbox(f.ax.snapLabel.c_str(), &st.snap);
  noteWidget("curve/snap");
  drawSelectedKeyEntry(f);
  return frameAllNow;
}

void drawCurveChannelList(CurveFrame& f) {
  CurveEditorState& st = f.st;
  ImGui::BeginChild("##channels", ImVec2(210.0f, 0.0f), true);
  ImGui::TextDisabled("%s", f.src.title().c_str());
  if (f.channels.empty()) ImGui::TextWrapped("%s", f.src.emptyHint().c_str());
  for (const auto& c : f.channels) {
    ImGui::PushID(c.name.c_str());
    bool shown = !hiddenChannel(st, c);
    const ImU32 color = channelColor(c.colorIndex);
    ImGui::PushStyleColor(ImGuiCol_CheckMark, ImGui::ColorConvertU32ToFloat4(color));
    if (ImGui::Checkbox("##show", &shown)) {
      auto key = std::make_pair(c.addr, c.channel);
      if (shown) st.hidden.erase(key);
      else st.hidden.insert(key);
    }
    ImGui::PopStyleColor();
    noteWidget("curve/channel/" + c.name);
    ImGui::SameLine();
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(color), "%s%s", c.name.c_str(), c.rotation ? " (deg)" : "");
    ImGui::PopID();
  }
  ImGui::EndChild();
}

void drawCurveGraph(const CurveFrame& f) {
  const CurveEditorState& st = f.st;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(f.g0, ImVec2(st.graphMax.x, st.graphMax.y), true);
  drawGraphGrid(f, dl);
  drawCurves(f, dl);
  drawPlayheads(f, dl);
  drawKeys(f, dl);
  if (st.drag == CurveEditorState::Drag::Box && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    const glm::vec2 mouse = f.mouse;
    ImVec2 a(std::min(st.dragStart.x, mouse.x), std::min(st.dragStart.y, mouse.y));
    ImVec2 b(std::max(st.dragStart.x, mouse.x), std::max(st.dragStart.y, mouse.y));
    dl->AddRectFilled(a, b, IM_COL32(90, 160, 255, 40));
    dl->AddRect(a, b, IM_COL32(90, 160, 255, 200));
  }
  dl->PopClipRect();
}

}  // namespace animorph
