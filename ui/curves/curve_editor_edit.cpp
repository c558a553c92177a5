// The curve editor's edits: every change to the keys (toolbar, key menu, numeric entry, adding a
// key, dragging keys and tangents) as one undoable command of the source (curve_editor_intern.h).
#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "ui/curves/curve_editor_intern.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

bool runCurveEdit(CurveFrame& f, const std::string& label, const KeyEditFn& fn) {
  auto cmd = f.src.edit(label, fn);
  if (cmd) f.doc.execute(std::move(*cmd));
  else f.status = {cmd.error(), true};
  return bool(cmd);
}

void setKeysInterp(CurveFrame& f, const std::vector<KeyRef>& keys, KeyInterp mode) {
  runCurveEdit(f, interpLabel(mode), [&](const TrackSet& s) { return setKeyInterp(s, keys, mode); });
}

void setKeysTangentMode(CurveFrame& f, const std::vector<KeyRef>& keys, bool user) {
  runCurveEdit(f, user ? "User tangents" : "Auto tangents",
               [&](const TrackSet& s) { return setKeyTangentMode(s, keys, user); });
}

void deleteCurveKeys(CurveFrame& f, const std::vector<KeyRef>& keys) {
  runCurveEdit(f, keysLabel("Delete", keys.size()), [&](const TrackSet& s) { return deleteKeys(s, keys); });
  f.st.selection.clear();
}

void drawSelectedKeyEntry(CurveFrame& f) {
  CurveEditorState& st = f.st;
  if (st.selection.size() != 1) return;
  const double xPerTime = f.ax.xPerTime;
  const KeyChannelRef k = *st.selection.begin();
  double t = 0.0;
  ParamSample v;
  if (!keyAt(f.src.track(k.key.param), k.key.key, t, v)) return;
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
  if (!commitFrame && !commitValue) return;
  KeyChannelRef moved = k;
  bool ok = runCurveEdit(f, "Set key", [&](const TrackSet& s) -> Status {
    auto r = setKeyTimeValue(s, k, x / xPerTime, value);
    if (!r) return Error{r.error()};
    moved = *r;
    return Status::success();
  });
  if (ok) st.selection = {moved};
}

namespace {

// The visible channel whose curve passes nearest the mouse (vertically) at x; null when none.
const CurveChannel* nearestCurve(const CurveFrame& f, double x) {
  const CurveChannel* best = nullptr;
  float bestPx = 1e30f;
  for (const auto& c : f.channels) {
    ParamSample v;
    if (hiddenChannel(f.st, c) || !sampleTrack(f.src.track(c.addr), x / f.ax.xPerTime, v)) continue;
    float d = std::abs(curveToPixel(f.st, x, channelOf(v, c.channel)).y - f.mouse.y);
    if (d < bestPx) {
      bestPx = d;
      best = &c;
    }
  }
  return best;
}

}  // namespace

bool addCurveKeyOnClick(CurveFrame& f) {
  CurveEditorState& st = f.st;
  bool addKey = f.hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
  if (f.hovered && ImGui::GetIO().KeyCtrl && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    addKey = true;
    for (const auto& k : f.keys) addKey &= glm::length(k.px - f.mouse) > kKeyPickPx;
  }
  if (!addKey) return false;
  const double x = pixelToCurve(st, f.mouse).x;
  if (const CurveChannel* best = nearestCurve(f, x)) {
    double t = x / f.ax.xPerTime;
    if (st.snap) t = std::round(x / f.ax.snapStep) * f.ax.snapStep / f.ax.xPerTime;
    const CurveChannel chosen = *best;
    int index = -1;
    bool ok = runCurveEdit(f, "Add key", [&](const TrackSet& s) -> Status {
      auto r = insertKey(s, chosen.addr, t);
      if (!r) return Error{r.error()};
      index = *r;
      return Status::success();
    });
    if (ok) st.selection = {KeyChannelRef{{chosen.addr, index}, chosen.channel}};
  }
  st.drag = CurveEditorState::Drag::None;
  return true;
}

namespace {

bool originalKey(const CurveFrame& f, const KeyChannelRef& k, double& t, ParamSample& v) {
  return keyAt(f.src.track(f.st.dragOriginal, k.key.param), k.key.key, t, v);
}

// Moves the dragged keys by the mouse's offset from where the drag began (snapped: the key under
// the mouse lands on a snap step, the others keep their offsets); one merged command per drag.
void dragMove(CurveFrame& f) {
  CurveEditorState& st = f.st;
  const ImGuiIO& io = ImGui::GetIO();
  double dx = (f.mouse.x - st.dragStart.x) / f.avail.x * (st.frame1 - st.frame0);
  double dv = -(f.mouse.y - st.dragStart.y) / f.avail.y * (st.value1 - st.value0);
  if (st.snap && !io.KeyCtrl) {
    double t0 = 0.0;
    ParamSample v0;
    originalKey(f, st.dragAnchor, t0, v0);
    double x0 = t0 * f.ax.xPerTime;
    dx = std::round((x0 + dx) / f.ax.snapStep) * f.ax.snapStep - x0;
  }
  double dt = dx / f.ax.xPerTime;
  if (dt == st.lastDt && dv == st.lastDv) return;
  st.lastDt = dt;
  st.lastDv = dv;
  std::vector<KeyChannelRef> moved;
  auto cmd = f.src.edit(
      keysLabel("Move", st.dragKeys.size()),
      [&](const TrackSet& s) -> Status {
        auto r = moveKeys(s, st.dragKeys, dt, float(dv));
        if (!r) return Error{r.error()};
        moved = *r;
        return Status::success();
      },
      f.mergeKey, &st.dragOriginal);
  if (cmd) {
    f.doc.execute(std::move(*cmd));
    st.selection = std::set<KeyChannelRef>(moved.begin(), moved.end());
    st.dragChanged = true;
  } else {
    f.status = {cmd.error(), true};
  }
}

// Sets the anchor key's slope to point its handle at the mouse (never back in time).
void dragTangent(CurveFrame& f) {
  CurveEditorState& st = f.st;
  double t0 = 0.0;
  ParamSample v0;
  if (!originalKey(f, st.dragAnchor, t0, v0)) return;
  glm::vec2 keyPx = curveToPixel(st, t0 * f.ax.xPerTime, channelOf(v0, st.dragAnchor.channel));
  glm::vec2 d = (f.mouse - keyPx) * float(st.tangentSide);
  if (d.x < 1.0f) d.x = 1.0f;  // a handle never turns back in time
  double dtSec = d.x / f.avail.x * (st.frame1 - st.frame0) / f.ax.xPerTime;
  double dVal = -d.y / f.avail.y * (st.value1 - st.value0);
  float slope = float(dVal / dtSec);
  if (slope == float(st.lastDv) && st.dragChanged) return;
  st.lastDv = slope;
  const KeyChannelRef anchor = st.dragAnchor;
  auto cmd = f.src.edit(
      "Change tangent", [&](const TrackSet& s) { return setKeyTangent(s, anchor, slope); }, f.mergeKey,
      &st.dragOriginal);
  if (cmd) f.doc.execute(std::move(*cmd));
  else f.status = {cmd.error(), true};
  st.dragChanged = true;
}

}  // namespace

void dragCurveKeys(CurveFrame& f) {
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) return;
  if (f.st.drag == CurveEditorState::Drag::Move) dragMove(f);
  else if (f.st.drag == CurveEditorState::Drag::Tangent) dragTangent(f);
}

void curveKeyShortcuts(CurveFrame& f) {
  const ImGuiIO& io = ImGui::GetIO();
  if (f.st.focused && !io.WantTextInput && !f.st.selection.empty() &&
      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false))
    deleteCurveKeys(f, selectedKeys(f.st));
}

void drawCurveKeyMenu(CurveFrame& f) {
  if (!ImGui::BeginPopup("##key_menu")) return;
  const std::vector<KeyRef> keys = selectedKeys(f.st);
  if (ImGui::MenuItem("Constant")) setKeysInterp(f, keys, KeyInterp::Constant);
  if (ImGui::MenuItem("Linear")) setKeysInterp(f, keys, KeyInterp::Linear);
  if (ImGui::MenuItem("Hermite")) setKeysInterp(f, keys, KeyInterp::Hermite);
  ImGui::Separator();
  if (ImGui::MenuItem("Auto tangents")) setKeysTangentMode(f, keys, false);
  if (ImGui::MenuItem("User tangents")) setKeysTangentMode(f, keys, true);
  ImGui::Separator();
  if (ImGui::MenuItem("Delete", "Del")) deleteCurveKeys(f, keys);
  ImGui::EndPopup();
}

}  // namespace animorph
