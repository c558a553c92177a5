#include "ui/curves/curve_editor_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "ui/curves/curve_source.h"
#include "ui/widgets/tool_window.h"
#include "ui/widgets/view_zoom.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

constexpr float kKeyPickPx = 6.0f;
constexpr float kHandlePx = 40.0f;  // on-screen length of a tangent handle

ImU32 channelColor(int index) {
  static const ImU32 kPalette[6] = {IM_COL32(240, 90, 90, 255),  IM_COL32(110, 215, 100, 255),
                                    IM_COL32(100, 150, 255, 255), IM_COL32(215, 120, 235, 255),
                                    IM_COL32(90, 215, 215, 255),  IM_COL32(235, 235, 240, 255)};
  if (index < 0 || index > 5) return IM_COL32(235, 200, 90, 255);
  return kPalette[index];
}

bool hiddenChannel(const CurveEditorState& st, const CurveChannel& c) {
  return st.hidden.count({c.addr, c.channel}) > 0;
}

std::vector<KeyRef> selectedKeys(const CurveEditorState& st) {
  std::set<KeyRef> keys;
  for (const auto& k : st.selection) keys.insert(k.key);
  return {keys.begin(), keys.end()};
}

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

// Grid line spacing: 1, 2, 5 x 10^k with at least minPx between lines.
double niceStep(double unitsPerPx, double minPx) {
  double raw = unitsPerPx * minPx;
  double p = std::pow(10.0, std::floor(std::log10(std::max(raw, 1e-12))));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
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
  const float h = std::clamp(area.size.y * 0.5f, 200.0f, 360.0f);
  if (!beginToolWindow("Curve Editor", ImVec2(area.min.x, area.min.y + area.size.y - h), ImVec2(area.size.x, h),
                       "curve/window", {st.visible, st.placeNext, st.focused}))
    return;

  std::unique_ptr<CurveSource> source =
      st.animorphosis ? makeAnimorphosisCurveSource(doc, st.animorphosisLinkA, st.animorphosisLinkB) : nullptr;
  if (!source) source = curveSourceForSelection(doc);
  if (!source) {
    ImGui::TextDisabled("Select a node of a BlobTree actor, or the morph (nothing selected), to see its curves.");
    ImGui::End();
    return;
  }
  const CurveSource& src = *source;
  if (st.sourceId != src.id()) {
    st.sourceId = src.id();
    st.selection.clear();
    st.frameAllNext = true;
    st.drag = CurveEditorState::Drag::None;
  }
  const CurveAxis ax = src.axis();
  const double xPerTime = ax.xPerTime;
  std::vector<CurveChannel> channels = src.channels();
  auto trackOf = [&](const KeyRef& k) { return src.track(k.param); };
  auto run = [&](const std::string& label, const KeyEditFn& fn) {
    auto cmd = src.edit(label, fn);
    if (cmd) doc.execute(std::move(*cmd));
    else status = {cmd.error(), true};
    return bool(cmd);
  };

  // The selection keeps only keys that still exist (undo, edits elsewhere).
  for (auto it = st.selection.begin(); it != st.selection.end();) {
    bool ok = it->key.key >= 0 && it->key.key < keyCount(trackOf(it->key));
    it = ok ? std::next(it) : st.selection.erase(it);
  }

  ImGuiIO& io = ImGui::GetIO();
  // ---- toolbar ----
  std::vector<KeyRef> selKeys = selectedKeys(st);
  bool haveSel = !selKeys.empty();
  auto setInterp = [&](KeyInterp mode) {
    run(interpLabel(mode), [&](const TrackSet& s) { return setKeyInterp(s, selKeys, mode); });
  };
  auto setTangentMode = [&](bool user) {
    run(user ? "User tangents" : "Auto tangents", [&](const TrackSet& s) { return setKeyTangentMode(s, selKeys, user); });
  };
  auto deleteSelected = [&]() {
    run(keysLabel("Delete", selKeys.size()), [&](const TrackSet& s) { return deleteKeys(s, selKeys); });
    st.selection.clear();
  };
  auto interpButton = [&](const char* label, KeyInterp mode, const char* key) {
    if (ImGui::Button(label) && haveSel) setInterp(mode);
    noteWidget(std::string("curve/") + key);
    ImGui::SameLine();
  };
  ImGui::BeginDisabled(!haveSel);
  interpButton("Constant", KeyInterp::Constant, "constant");
  interpButton("Linear", KeyInterp::Linear, "linear");
  interpButton("Hermite", KeyInterp::Hermite, "hermite");
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  if (ImGui::Button("Auto tangents")) setTangentMode(false);
  noteWidget("curve/auto_tangents");
  ImGui::SameLine();
  if (ImGui::Button("User tangents")) setTangentMode(true);
  noteWidget("curve/user_tangents");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  bool frameAllNow = ImGui::Button("Frame all (F)");
  noteWidget("curve/frame_all");
  ImGui::SameLine();
  ImGui::Checkbox(ax.snapLabel.c_str(), &st.snap);
  noteWidget("curve/snap");
  if (st.selection.size() == 1) {
    const KeyChannelRef k = *st.selection.begin();
    double t = 0.0;
    ParamSample v;
    if (keyAt(trackOf(k.key), k.key.key, t, v)) {
      ImGui::SameLine();
      ImGui::TextDisabled("|");
      ImGui::SameLine();
      double x = t * xPerTime;
      float value = channelOf(v, k.channel);
      ImGui::AlignTextToFramePadding();
      ImGui::TextUnformatted(xPerTime == 1.0 ? "u" : "Frame");
      ImGui::SameLine();
      ImGui::SetNextItemWidth(70.0f);
      ImGui::InputDouble("##key_frame", &x, 0.0, 0.0, xPerTime == 1.0 ? "%.3f" : "%.2f");
      noteWidget("curve/key_frame");
      bool commitFrame = ImGui::IsItemDeactivatedAfterEdit();
      ImGui::SameLine();
      ImGui::TextUnformatted("Value");
      ImGui::SameLine();
      ImGui::SetNextItemWidth(80.0f);
      ImGui::InputFloat("##key_value", &value, 0.0f, 0.0f, "%.4g");
      noteWidget("curve/key_value");
      bool commitValue = ImGui::IsItemDeactivatedAfterEdit();
      if (commitFrame || commitValue) {
        KeyChannelRef moved = k;
        bool ok = run("Set key", [&](const TrackSet& s) -> Status {
          auto r = setKeyTimeValue(s, k, x / xPerTime, value);
          if (!r) return Error{r.error()};
          moved = *r;
          return Status::success();
        });
        if (ok) st.selection = {moved};
      }
    }
  }

  // ---- channel list ----
  ImGui::BeginChild("##channels", ImVec2(210.0f, 0.0f), true);
  ImGui::TextDisabled("%s", src.title().c_str());
  if (channels.empty()) ImGui::TextWrapped("%s", src.emptyHint().c_str());
  for (const auto& c : channels) {
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
  ImGui::SameLine();

  // ---- graph ----
  ImVec2 avail = ImGui::GetContentRegionAvail();
  avail.x = std::max(avail.x, 50.0f);
  avail.y = std::max(avail.y, 50.0f);
  ImVec2 g0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##graph", avail,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle |
                             ImGuiButtonFlags_MouseButtonRight);
  noteWidget("curve/graph");
  const bool hovered = ImGui::IsItemHovered();
  const bool active = ImGui::IsItemActive();
  st.graphMin = {g0.x, g0.y};
  st.graphMax = {g0.x + avail.x, g0.y + avail.y};
  if (st.frameAllNext || frameAllNow || (st.focused && !io.WantTextInput && ImGui::IsKeyPressed('F', false) &&
                                         !io.KeyCtrl && !io.KeyAlt)) {
    frameAll(st, src, channels, ax);
    st.frameAllNext = false;
  }
  const glm::vec2 mouse(io.MousePos.x, io.MousePos.y);

  // Zoom (wheel: x, Ctrl+wheel: values) around the mouse; middle drag pans.
  if (hovered && io.MouseWheel != 0.0f) {
    glm::dvec2 pivot = pixelToCurve(st, mouse);
    if (io.KeyCtrl)
      scaleSpanAround(st.value0, st.value1, pivot.y, wheelSpanFactor(io.MouseWheel));
    else
      scaleSpanAround(st.frame0, st.frame1, pivot.x, wheelSpanFactor(io.MouseWheel));
  }
  if (active && ImGui::IsMouseDown(ImGuiMouseButton_Middle) && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    panSpan(st.frame0, st.frame1, io.MouseDelta.x, avail.x);
    panSpan(st.value0, st.value1, io.MouseDelta.y, avail.y, /*contentUp=*/true);
  }

  // Key positions of the visible channels.
  struct KeyPx {
    KeyChannelRef ref;
    glm::vec2 px;
    KeyInterp interp;
    bool rotation;
  };
  std::vector<KeyPx> keys;
  for (const auto& c : channels) {
    if (hiddenChannel(st, c)) continue;
    ConstTrackPtr tp = src.track(c.addr);
    for (int k = 0, n = keyCount(tp); k < n; ++k) {
      double t = 0.0;
      ParamSample v;
      KeyInterp interp = KeyInterp::Hermite;
      if (!keyAt(tp, k, t, v, &interp)) continue;
      keys.push_back({{{c.addr, k}, c.channel}, curveToPixel(st, t * xPerTime, channelOf(v, c.channel)), interp, c.rotation});
    }
  }
  auto handleDir = [&](const KeyChannelRef& k) {
    float slope = keySlope(trackOf(k.key), k.key.key, k.channel);  // value per time unit
    glm::vec2 d(float(xPerTime / (st.frame1 - st.frame0) * avail.x), float(-slope / (st.value1 - st.value0) * avail.y));
    float len = glm::length(d);
    return len > 0.0f ? d / len * kHandlePx : glm::vec2(kHandlePx, 0.0f);
  };
  auto showsHandles = [&](const KeyPx& k) { return !k.rotation && st.selection.count(k.ref); };

  // ---- mouse: press ----
  const std::string mergeKey = "curve/" + src.id();
  // Double-click, or Ctrl+click off the keys: a key on the nearest visible curve at the mouse's x.
  bool addKey = hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
  if (hovered && io.KeyCtrl && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    addKey = true;
    for (const auto& k : keys) addKey &= glm::length(k.px - mouse) > kKeyPickPx;
  }
  if (addKey) {
    const double x = pixelToCurve(st, mouse).x;
    const CurveChannel* best = nullptr;
    float bestPx = 1e30f;
    for (const auto& c : channels) {
      ParamSample v;
      if (hiddenChannel(st, c) || !sampleTrack(src.track(c.addr), x / xPerTime, v)) continue;
      float d = std::abs(curveToPixel(st, x, channelOf(v, c.channel)).y - mouse.y);
      if (d < bestPx) {
        bestPx = d;
        best = &c;
      }
    }
    if (best) {
      double t = x / xPerTime;
      if (st.snap) t = std::round(x / ax.snapStep) * ax.snapStep / xPerTime;
      const CurveChannel chosen = *best;
      int index = -1;
      bool ok = run("Add key", [&](const TrackSet& s) -> Status {
        auto r = insertKey(s, chosen.addr, t);
        if (!r) return Error{r.error()};
        index = *r;
        return Status::success();
      });
      if (ok) st.selection = {KeyChannelRef{{chosen.addr, index}, chosen.channel}};
    }
    st.drag = CurveEditorState::Drag::None;
  } else if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    st.dragStart = mouse;
    st.drag = CurveEditorState::Drag::Box;
    // Tangent handles of selected keys first, then keys.
    for (const auto& k : keys) {
      if (!showsHandles(k)) continue;
      glm::vec2 d = handleDir(k.ref);
      for (int side : {-1, 1}) {
        if (glm::length(k.px + float(side) * d - mouse) <= kKeyPickPx) {
          st.drag = CurveEditorState::Drag::Tangent;
          st.dragAnchor = k.ref;
          st.tangentSide = side;
        }
      }
    }
    if (st.drag == CurveEditorState::Drag::Box) {
      const KeyPx* hit = nullptr;
      float best = kKeyPickPx;
      for (const auto& k : keys) {
        float d = glm::length(k.px - mouse);
        if (d <= best) {
          best = d;
          hit = &k;
        }
      }
      if (hit) {
        if (io.KeyShift) {
          if (!st.selection.erase(hit->ref)) st.selection.insert(hit->ref);
        } else if (!st.selection.count(hit->ref)) {
          st.selection = {hit->ref};
        }
        if (st.selection.count(hit->ref)) {
          st.drag = CurveEditorState::Drag::Move;
          st.dragAnchor = hit->ref;
        } else {
          st.drag = CurveEditorState::Drag::None;
        }
      }
    }
    if (st.drag == CurveEditorState::Drag::Move || st.drag == CurveEditorState::Drag::Tangent) {
      st.dragOriginal = src.snapshot();
      st.dragKeys.assign(st.selection.begin(), st.selection.end());
      st.lastDt = st.lastDv = 0.0;
      st.dragChanged = false;
      doc.beginDrag();
    }
  }
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
    for (const auto& k : keys)
      if (glm::length(k.px - mouse) <= kKeyPickPx) {
        if (!st.selection.count(k.ref)) st.selection = {k.ref};
        ImGui::OpenPopup("##key_menu");
        break;
      }
  }

  // ---- mouse: drag ----
  bool leftDown = ImGui::IsMouseDown(ImGuiMouseButton_Left);
  auto originalKey = [&](const KeyChannelRef& k, double& t, ParamSample& v) {
    return keyAt(src.track(st.dragOriginal, k.key.param), k.key.key, t, v);
  };
  if (st.drag == CurveEditorState::Drag::Move && leftDown) {
    double dx = (mouse.x - st.dragStart.x) / avail.x * (st.frame1 - st.frame0);
    double dv = -(mouse.y - st.dragStart.y) / avail.y * (st.value1 - st.value0);
    if (st.snap && !io.KeyCtrl) {
      // The key under the mouse lands on a snap step; the others keep their offsets.
      double t0 = 0.0;
      ParamSample v0;
      originalKey(st.dragAnchor, t0, v0);
      double x0 = t0 * xPerTime;
      dx = std::round((x0 + dx) / ax.snapStep) * ax.snapStep - x0;
    }
    double dt = dx / xPerTime;
    if (dt != st.lastDt || dv != st.lastDv) {
      st.lastDt = dt;
      st.lastDv = dv;
      std::vector<KeyChannelRef> moved;
      auto cmd = src.edit(
          keysLabel("Move", st.dragKeys.size()),
          [&](const TrackSet& s) -> Status {
            auto r = moveKeys(s, st.dragKeys, dt, float(dv));
            if (!r) return Error{r.error()};
            moved = *r;
            return Status::success();
          },
          mergeKey, &st.dragOriginal);
      if (cmd) {
        doc.execute(std::move(*cmd));
        st.selection = std::set<KeyChannelRef>(moved.begin(), moved.end());
        st.dragChanged = true;
      } else {
        status = {cmd.error(), true};
      }
    }
  } else if (st.drag == CurveEditorState::Drag::Tangent && leftDown) {
    double t0 = 0.0;
    ParamSample v0;
    if (originalKey(st.dragAnchor, t0, v0)) {
      glm::vec2 keyPx = curveToPixel(st, t0 * xPerTime, channelOf(v0, st.dragAnchor.channel));
      glm::vec2 d = (mouse - keyPx) * float(st.tangentSide);
      if (d.x < 1.0f) d.x = 1.0f;  // a handle never turns back in time
      double dtSec = d.x / avail.x * (st.frame1 - st.frame0) / xPerTime;
      double dVal = -d.y / avail.y * (st.value1 - st.value0);
      float slope = float(dVal / dtSec);
      if (slope != float(st.lastDv) || !st.dragChanged) {
        st.lastDv = slope;
        const KeyChannelRef anchor = st.dragAnchor;
        auto cmd = src.edit(
            "Change tangent", [&](const TrackSet& s) { return setKeyTangent(s, anchor, slope); }, mergeKey,
            &st.dragOriginal);
        if (cmd) doc.execute(std::move(*cmd));
        else status = {cmd.error(), true};
        st.dragChanged = true;
      }
    }
  }
  // ---- mouse: release ----
  if (st.drag != CurveEditorState::Drag::None && !leftDown) {
    if (st.drag == CurveEditorState::Drag::Box) {
      glm::vec2 lo = glm::min(st.dragStart, mouse), hi = glm::max(st.dragStart, mouse);
      if (!io.KeyShift) st.selection.clear();
      for (const auto& k : keys)
        if (k.px.x >= lo.x && k.px.x <= hi.x && k.px.y >= lo.y && k.px.y <= hi.y) st.selection.insert(k.ref);
    } else if (st.drag == CurveEditorState::Drag::Move || st.drag == CurveEditorState::Drag::Tangent) {
      doc.endDrag();
      st.dragOriginal.reset();
    }
    st.drag = CurveEditorState::Drag::None;
  }

  // ---- keyboard: Del deletes the selected keys ----
  if (st.focused && !io.WantTextInput && !st.selection.empty() &&
      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false)) {
    selKeys = selectedKeys(st);
    deleteSelected();
  }

  // ---- context menu of a key ----
  if (ImGui::BeginPopup("##key_menu")) {
    selKeys = selectedKeys(st);
    if (ImGui::MenuItem("Constant")) setInterp(KeyInterp::Constant);
    if (ImGui::MenuItem("Linear")) setInterp(KeyInterp::Linear);
    if (ImGui::MenuItem("Hermite")) setInterp(KeyInterp::Hermite);
    ImGui::Separator();
    if (ImGui::MenuItem("Auto tangents")) setTangentMode(false);
    if (ImGui::MenuItem("User tangents")) setTangentMode(true);
    ImGui::Separator();
    if (ImGui::MenuItem("Delete", "Del")) deleteSelected();
    ImGui::EndPopup();
  }

  // ---- drawing ----
  ImDrawList* dl = ImGui::GetWindowDrawList();
  ImVec2 g1(st.graphMax.x, st.graphMax.y);
  dl->PushClipRect(g0, g1, true);
  dl->AddRectFilled(g0, g1, IM_COL32(30, 30, 34, 255));
  // The range (playback range, or u in [0, 1]) in a lighter tone.
  {
    float rx0 = curveToPixel(st, ax.rangeStart, 0.0).x, rx1 = curveToPixel(st, ax.rangeEnd, 0.0).x;
    dl->AddRectFilled(ImVec2(std::max(g0.x, rx0), g0.y), ImVec2(std::min(g1.x, rx1), g1.y), IM_COL32(38, 38, 44, 255));
  }
  // Grid with labels: x along the bottom, values along the left.
  char buf[32];
  const float lineH = ImGui::GetTextLineHeight();
  double fStep = niceStep((st.frame1 - st.frame0) / avail.x, 60.0);
  if (xPerTime != 1.0) fStep = std::max(1.0, fStep);  // whole frames
  for (double f = std::ceil(st.frame0 / fStep) * fStep; f <= st.frame1; f += fStep) {
    float x = curveToPixel(st, f, 0.0).x;
    dl->AddLine(ImVec2(x, g0.y), ImVec2(x, g1.y), IM_COL32(55, 55, 62, 255));
    std::snprintf(buf, sizeof buf, "%g", std::abs(f) < fStep * 1e-6 ? 0.0 : f);  // never "-0"
    dl->AddText(ImVec2(x + 3.0f, g1.y - lineH - 2.0f), IM_COL32(150, 150, 160, 255), buf);
  }
  double vStep = niceStep((st.value1 - st.value0) / avail.y, 40.0);
  for (double v = std::ceil(st.value0 / vStep) * vStep; v <= st.value1; v += vStep) {
    float y = curveToPixel(st, 0.0, v).y;
    bool zero = std::abs(v) < vStep * 1e-3;
    dl->AddLine(ImVec2(g0.x, y), ImVec2(g1.x, y), zero ? IM_COL32(85, 85, 95, 255) : IM_COL32(55, 55, 62, 255));
    std::snprintf(buf, sizeof buf, "%g", zero ? 0.0 : v);
    dl->AddText(ImVec2(g0.x + 3.0f, y - lineH), IM_COL32(150, 150, 160, 255), buf);
  }
  // The axis' name, bottom right.
  {
    ImVec2 sz = ImGui::CalcTextSize(ax.label.c_str());
    dl->AddText(ImVec2(g1.x - sz.x - 6.0f, g1.y - 2.0f * lineH - 4.0f), IM_COL32(170, 170, 185, 255), ax.label.c_str());
  }
  // Curves, sampled every 2 pixels.
  for (const auto& c : channels) {
    if (hiddenChannel(st, c)) continue;
    ConstTrackPtr tp = src.track(c.addr);
    std::vector<ImVec2> pts;
    for (float x = g0.x; x <= g1.x + 2.0f; x += 2.0f) {
      double fx = pixelToCurve(st, {x, 0.0f}).x;
      ParamSample v;
      if (!sampleTrack(tp, fx / xPerTime, v)) break;
      glm::vec2 p = curveToPixel(st, fx, channelOf(v, c.channel));
      pts.push_back(ImVec2(p.x, std::clamp(p.y, g0.y - 1000.0f, g1.y + 1000.0f)));
    }
    if (pts.size() >= 2) dl->AddPolyline(pts.data(), int(pts.size()), channelColor(c.colorIndex), 0, 1.5f);
  }
  // Playheads: the current frame (or its progress u).
  for (const CurvePlayhead& ph : ax.playheads) {
    const ImU32 col = ph.secondary ? IM_COL32(240, 160, 70, 255) : IM_COL32(90, 160, 255, 255);
    float cx = curveToPixel(st, ph.x, 0.0).x;
    dl->AddLine(ImVec2(cx, g0.y), ImVec2(cx, g1.y), col, 2.0f);
    if (!ph.label.empty()) {
      std::snprintf(buf, sizeof buf, "%.2f", ph.x);
      dl->AddText(ImVec2(cx + 4.0f, g0.y + 2.0f + (ph.secondary ? lineH : 0.0f)), col, (ph.label + " " + buf).c_str());
    }
  }
  // Keys and the handles of selected ones.
  for (const auto& k : keys) {
    bool sel = st.selection.count(k.ref) > 0;
    if (showsHandles(k)) {
      glm::vec2 d = handleDir(k.ref);
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
  if (st.drag == CurveEditorState::Drag::Box && leftDown) {
    ImVec2 a(std::min(st.dragStart.x, mouse.x), std::min(st.dragStart.y, mouse.y));
    ImVec2 b(std::max(st.dragStart.x, mouse.x), std::max(st.dragStart.y, mouse.y));
    dl->AddRectFilled(a, b, IM_COL32(90, 160, 255, 40));
    dl->AddRect(a, b, IM_COL32(90, 160, 255, 200));
  }
  dl->PopClipRect();
  ImGui::End();
}

}  // namespace animorph
