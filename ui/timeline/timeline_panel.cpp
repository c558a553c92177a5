#include "ui/timeline/timeline_panel.h"

#include "ui/common/panel_window.h"

#include "ui/timeline/animorphosis_markers.h"
#include "ui/timeline/morph_markers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/doc/project_commands.h"
#include "ui/timeline/transport.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

int rulerLabelStep(double pixelsPerFrame, double minLabelPx) {
  if (!(pixelsPerFrame > 0.0)) return 1;
  static const int kMantissa[] = {1, 2, 5};
  for (long decade = 1; decade < 100000000; decade *= 10)
    for (int m : kMantissa)
      if (m * decade * pixelsPerFrame >= minLabelPx) return static_cast<int>(m * decade);
  return 100000000;
}

namespace {

void fitView(TimelineState& st, const Timeline& tl) {
  double len = std::max(1, tl.frameEnd - tl.frameStart);
  double margin = std::max(1.0, len * 0.03);
  st.viewStartFrame = tl.frameStart - margin;
  st.viewEndFrame = tl.frameEnd + margin;
}

void drawRuler(Document& doc, Playback& playback, const std::vector<int>& keyFrames, TimelineState& st,
               DragMerge& drag) {
  const Timeline& tl = doc.project().timeline;
  if (st.fitToRange) fitView(st, tl);
  ImVec2 size = ImGui::GetContentRegionAvail();
  size.x = std::max(size.x, 10.0f);
  size.y = std::max(size.y, 24.0f);
  ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##ruler", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle);
  noteWidget("timeline/ruler");
  bool hovered = ImGui::IsItemHovered();
  bool active = ImGui::IsItemActive();
  ImGuiIO& io = ImGui::GetIO();

  double span = std::max(1e-3, st.viewEndFrame - st.viewStartFrame);
  double pxPerFrame = size.x / span;
  auto frameAt = [&](float x) { return st.viewStartFrame + (x - p0.x) / pxPerFrame; };
  auto xOf = [&](double f) { return static_cast<float>(p0.x + (f - st.viewStartFrame) * pxPerFrame); };

  // Zoom around the mouse, pan with the middle button.
  if (hovered && io.MouseWheel != 0.0f) {
    double pivot = frameAt(io.MousePos.x);
    double factor = std::pow(0.85, io.MouseWheel);
    double newSpan = std::clamp(span * factor, 4.0, 1e6);
    st.viewStartFrame = pivot - (pivot - st.viewStartFrame) * newSpan / span;
    st.viewEndFrame = st.viewStartFrame + newSpan;
    st.fitToRange = false;
    span = newSpan;
    pxPerFrame = size.x / span;
  }
  if (active && ImGui::IsMouseDown(ImGuiMouseButton_Middle) && io.MouseDelta.x != 0.0f) {
    double d = io.MouseDelta.x / pxPerFrame;
    st.viewStartFrame -= d;
    st.viewEndFrame -= d;
    st.fitToRange = false;
  }
  if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Middle)) st.fitToRange = true;

  // Scrub: click or drag anywhere on the ruler.
  // A press on a morph or animorphosis marker's handle drags that marker instead of scrubbing;
  // the whole drag is one undo step.
  drag.begin(doc);
  if (ImGui::IsItemActivated() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    const glm::vec2 mouse(io.MousePos.x, io.MousePos.y);
    st.draggingMarker = morphMarkerAt(doc, mouse, p0.x, p0.x + size.x, p0.y, p0.y + size.y, st.viewStartFrame,
                                      st.viewEndFrame);
    if (st.draggingMarker < 0) {
      int m = animorphosisMarkerAt(doc, mouse, p0.x, p0.x + size.x, p0.y + size.y, st.viewStartFrame, st.viewEndFrame);
      if (m >= 0) st.draggingMarker = kAnimorphosisMarker0 + m;
    }
  }
  if (st.draggingMarker >= 0) {
    const int f = static_cast<int>(std::lround(frameAt(io.MousePos.x)));
    if (active && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      if (st.draggingMarker >= kAnimorphosisMarker0) moveAnimorphosisMarker(doc, st.draggingMarker - kAnimorphosisMarker0, f);
      else moveMorphMarker(doc, st.draggingMarker, f);
    } else
      st.draggingMarker = -1;
  }
  drag.end(doc);
  st.scrubbing = active && ImGui::IsMouseDown(ImGuiMouseButton_Left) && st.draggingMarker < 0;
  if (st.scrubbing) {
    int f = static_cast<int>(std::lround(frameAt(io.MousePos.x)));
    f = std::clamp(f, tl.frameStart, std::max(tl.frameStart, tl.frameEnd));
    if (f != tl.currentFrame || ImGui::IsItemActivated()) goToFrame(doc, playback, f);
  }

  ImDrawList* dl = ImGui::GetWindowDrawList();
  ImVec2 p1(p0.x + size.x, p0.y + size.y);
  dl->PushClipRect(p0, p1, true);
  // Frames inside the playback range are lighter. Each pixel is filled once: the darker parts either
  // side of the range, then the range (on a CPU Vulkan device the UI's cost follows the pixels it
  // shades, and a full background under the range doubled the ruler's).
  const ImU32 outside = IM_COL32(30, 30, 34, 255);
  float rx0 = std::max(p0.x, xOf(tl.frameStart)), rx1 = std::min(p1.x, xOf(tl.frameEnd));
  if (rx1 > rx0) {
    if (rx0 > p0.x) dl->AddRectFilled(p0, ImVec2(rx0, p1.y), outside);
    if (rx1 < p1.x) dl->AddRectFilled(ImVec2(rx1, p0.y), p1, outside);
    dl->AddRectFilled(ImVec2(rx0, p0.y), ImVec2(rx1, p1.y), IM_COL32(48, 48, 54, 255));
  } else {
    dl->AddRectFilled(p0, p1, outside);
  }

  int step = rulerLabelStep(pxPerFrame);
  int minor = step >= 5 && step % 5 == 0 ? step / 5 : (step % 2 == 0 ? step / 2 : step);
  if (minor * pxPerFrame < 5.0) minor = step;
  long first = static_cast<long>(std::floor(st.viewStartFrame / minor)) * minor;
  for (long f = first; f <= st.viewEndFrame; f += minor) {
    float x = xOf(static_cast<double>(f));
    bool major = f % step == 0;
    float h = major ? size.y * 0.45f : size.y * 0.2f;
    dl->AddLine(ImVec2(x, p0.y), ImVec2(x, p0.y + h), major ? IM_COL32(170, 170, 180, 255) : IM_COL32(100, 100, 110, 255));
    if (major && x + 3.0f >= p0.x) {  // a label cut at the left edge would misread ("-5" as "5")
      char buf[24];
      std::snprintf(buf, sizeof buf, "%ld", f);
      // Below the minor ticks, so no tick line crosses the digits.
      dl->AddText(ImVec2(x + 3.0f, p0.y + size.y * 0.2f + 1.0f), IM_COL32(200, 200, 210, 255), buf);
    }
  }
  // Key ticks of the selection.
  float ky = p0.y + size.y * 0.75f;
  for (int k : keyFrames) {
    float x = xOf(k);
    if (x < p0.x - 5.0f || x > p1.x + 5.0f) continue;
    dl->AddQuadFilled(ImVec2(x, ky - 5.0f), ImVec2(x + 4.0f, ky), ImVec2(x, ky + 5.0f), ImVec2(x - 4.0f, ky),
                      IM_COL32(240, 200, 60, 255));
  }
  drawMorphMarkers(doc, p0.x, p1.x, p0.y, p1.y, st.viewStartFrame, st.viewEndFrame);
  drawAnimorphosisInterval(doc, p0.x, p1.x, p0.y, p1.y, st.viewStartFrame, st.viewEndFrame);
  // Current frame.
  float cx = xOf(tl.currentFrame);
  dl->AddLine(ImVec2(cx, p0.y), ImVec2(cx, p1.y), IM_COL32(90, 160, 255, 255), 2.0f);
  char cur[24];
  std::snprintf(cur, sizeof cur, "%d", tl.currentFrame);
  ImVec2 ts = ImGui::CalcTextSize(cur);
  dl->AddRectFilled(ImVec2(cx - ts.x * 0.5f - 3.0f, p1.y - ts.y - 2.0f), ImVec2(cx + ts.x * 0.5f + 3.0f, p1.y),
                    IM_COL32(90, 160, 255, 255), 3.0f);
  dl->AddText(ImVec2(cx - ts.x * 0.5f, p1.y - ts.y - 1.0f), IM_COL32(10, 10, 20, 255), cur);
  dl->PopClipRect();
}

// A field's label on its left, the way DCC transport bars read ("Speed 1.00x").
void labelBefore(const char* label) {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted(label);
  ImGui::SameLine();
}

}  // namespace

void drawTimelinePanel(const LayoutRect& rect, Document& doc, Playback& playback, const std::vector<int>& keyFrames,
                       TimelineState& st, DragMerge& drag, std::vector<Action>& actions) {
  if (!beginPanelWindow("Timeline", rect,
                        ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse))
    return;
  const Timeline tl = doc.project().timeline;  // copy: commands below change it

  auto button = [&](const char* label, Action a, const char* key) {
    if (ImGui::Button(label)) actions.push_back(a);
    noteWidget(std::string("timeline/") + key);
    if (ImGui::IsItemHovered()) {
      std::string hint = shortcutHint(a);
      ImGui::SetTooltip("%s%s%s%s", key, hint.empty() ? "" : " (", hint.c_str(), hint.empty() ? "" : ")");
    }
    ImGui::SameLine();
  };
  button("|<", Action::GoToStart, "start");
  button("<", Action::StepBack, "back");
  button(playback.playing() ? "Pause" : "Play", Action::PlayPause, "play");
  button(">", Action::StepForward, "forward");
  button(">|", Action::GoToEnd, "end");

  bool loop = tl.loop;
  if (ImGui::Checkbox("Loop", &loop))
    doc.execute(setTimelineField(doc.project(), &Timeline::loop, loop, loop ? "Loop playback" : "Play once"));
  noteWidget("timeline/loop");
  ImGui::SameLine();

  labelBefore("Speed");
  ImGui::SetNextItemWidth(70.0f);
  double speed = tl.playbackSpeed;
  bool changed = ImGui::DragScalar("##speed", ImGuiDataType_Double, &speed, 0.01f, nullptr, nullptr, "%.2fx");
  drag.begin(doc);
  if (changed)
    doc.execute(setTimelineField(doc.project(), &Timeline::playbackSpeed, speed, "Set playback speed", "tl/speed"));
  drag.end(doc);
  ImGui::SameLine();

  labelBefore("FPS");
  ImGui::SetNextItemWidth(60.0f);
  double fps = tl.fps;
  ImGui::InputDouble("##fps", &fps, 0.0, 0.0, "%.3g");
  noteWidget("timeline/fps");
  if (ImGui::IsItemDeactivatedAfterEdit() && fps != tl.fps)
    doc.execute(setTimelineField(doc.project(), &Timeline::fps, std::clamp(fps, 1.0, 1000.0), "Set frame rate"));
  ImGui::SameLine();

  labelBefore("Start");
  ImGui::SetNextItemWidth(60.0f);
  int start = tl.frameStart;
  ImGui::InputInt("##start", &start, 0, 0);
  noteWidget("timeline/range_start");
  if (ImGui::IsItemDeactivatedAfterEdit() && start != tl.frameStart) {
    start = std::min(start, tl.frameEnd);
    doc.execute(setTimelineField(doc.project(), &Timeline::frameStart, start, "Set range start"));
    goToFrame(doc, playback, tl.currentFrame);
  }
  ImGui::SameLine();
  labelBefore("End");
  ImGui::SetNextItemWidth(60.0f);
  int end = tl.frameEnd;
  ImGui::InputInt("##end", &end, 0, 0);
  noteWidget("timeline/range_end");
  if (ImGui::IsItemDeactivatedAfterEdit() && end != tl.frameEnd) {
    end = std::max(end, tl.frameStart);
    doc.execute(setTimelineField(doc.project(), &Timeline::frameEnd, end, "Set range end"));
    goToFrame(doc, playback, tl.currentFrame);
  }
  ImGui::SameLine();
  labelBefore("Frame");
  ImGui::SetNextItemWidth(60.0f);
  int frame = tl.currentFrame;
  ImGui::InputInt("##frame", &frame, 0, 0);
  noteWidget("timeline/frame");
  if (ImGui::IsItemDeactivatedAfterEdit()) goToFrame(doc, playback, frame);
  ImGui::SameLine();
  ImGui::TextDisabled("%.2f s", tl.currentTimeSec());

  drawRuler(doc, playback, keyFrames, st, drag);
  ImGui::End();
}

}  // namespace animorph
