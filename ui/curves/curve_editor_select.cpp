// The curve editor's picking and selection: which keys are on screen, which key or handle a click
// hits, box selection, and the selection kept valid across edits (curve_editor_intern.h).
#include <algorithm>
#include <set>

#include <imgui.h>

#include "ui/curves/curve_editor_intern.h"

namespace animorph {

bool hiddenChannel(const CurveEditorState& st, const CurveChannel& c) {
  return st.hidden.count({c.addr, c.channel}) > 0;
}

std::vector<KeyRef> selectedKeys(const CurveEditorState& st) {
  std::set<KeyRef> keys;
  for (const auto& k : st.selection) keys.insert(k.key);
  return {keys.begin(), keys.end()};
}

void pruneCurveSelection(CurveFrame& f) {
  auto& selection = f.st.selection;
  for (auto it = selection.begin(); it != selection.end();) {
    bool ok = it->key.key >= 0 && it->key.key < keyCount(f.src.track(it->key.param));
    it = ok ? std::next(it) : selection.erase(it);
  }
}

void collectCurveKeys(CurveFrame& f) {
  f.keys.clear();
  for (const auto& c : f.channels) {
    if (hiddenChannel(f.st, c)) continue;
    ConstTrackPtr tp = f.src.track(c.addr);
    for (int k = 0, n = keyCount(tp); k < n; ++k) {
      double t = 0.0;
      ParamSample v;
      KeyInterp interp = KeyInterp::Hermite;
      if (!keyAt(tp, k, t, v, &interp)) continue;
      f.keys.push_back(
          {{{c.addr, k}, c.channel}, curveToPixel(f.st, t * f.ax.xPerTime, channelOf(v, c.channel)), interp, c.rotation});
    }
  }
}

glm::vec2 handleDir(const CurveFrame& f, const KeyChannelRef& k) {
  const CurveEditorState& st = f.st;
  float slope = keySlope(f.src.track(k.key.param), k.key.key, k.channel);  // value per time unit
  glm::vec2 d(float(f.ax.xPerTime / (st.frame1 - st.frame0) * f.avail.x),
              float(-slope / (st.value1 - st.value0) * f.avail.y));
  float len = glm::length(d);
  return len > 0.0f ? d / len * kHandlePx : glm::vec2(kHandlePx, 0.0f);
}

bool showsHandles(const CurveFrame& f, const CurveKeyPx& k) { return !k.rotation && f.st.selection.count(k.ref); }

namespace {

// Tangent handles of selected keys first: a hit starts a tangent drag.
void pickHandle(CurveFrame& f) {
  CurveEditorState& st = f.st;
  for (const auto& k : f.keys) {
    if (!showsHandles(f, k)) continue;
    glm::vec2 d = handleDir(f, k.ref);
    for (int side : {-1, 1}) {
      if (glm::length(k.px + float(side) * d - f.mouse) <= kKeyPickPx) {
        st.drag = CurveEditorState::Drag::Tangent;
        st.dragAnchor = k.ref;
        st.tangentSide = side;
      }
    }
  }
}

// Then the nearest key within reach: selected (Shift toggles) and, when selected, moved.
void pickKey(CurveFrame& f) {
  CurveEditorState& st = f.st;
  const CurveKeyPx* hit = nullptr;
  float best = kKeyPickPx;
  for (const auto& k : f.keys) {
    float d = glm::length(k.px - f.mouse);
    if (d <= best) {
      best = d;
      hit = &k;
    }
  }
  if (!hit) return;
  if (ImGui::GetIO().KeyShift) {
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

}  // namespace

void pressOnCurveGraph(CurveFrame& f) {
  CurveEditorState& st = f.st;
  st.dragStart = f.mouse;
  st.drag = CurveEditorState::Drag::Box;
  pickHandle(f);
  if (st.drag == CurveEditorState::Drag::Box) pickKey(f);
  if (st.drag == CurveEditorState::Drag::Move || st.drag == CurveEditorState::Drag::Tangent) {
    st.dragOriginal = f.src.snapshot();
    st.dragKeys.assign(st.selection.begin(), st.selection.end());
    st.lastDt = st.lastDv = 0.0;
    st.dragChanged = false;
    f.doc.beginDrag();
  }
}

void rightClickCurveKey(CurveFrame& f) {
  for (const auto& k : f.keys)
    if (glm::length(k.px - f.mouse) <= kKeyPickPx) {
      if (!f.st.selection.count(k.ref)) f.st.selection = {k.ref};
      ImGui::OpenPopup("##key_menu");
      break;
    }
}

void releaseCurveDrag(CurveFrame& f) {
  CurveEditorState& st = f.st;
  if (st.drag == CurveEditorState::Drag::None || ImGui::IsMouseDown(ImGuiMouseButton_Left)) return;
  if (st.drag == CurveEditorState::Drag::Box) {
    glm::vec2 lo = glm::min(st.dragStart, f.mouse), hi = glm::max(st.dragStart, f.mouse);
    if (!ImGui::GetIO().KeyShift) st.selection.clear();
    for (const auto& k : f.keys)
      if (k.px.x >= lo.x && k.px.x <= hi.x && k.px.y >= lo.y && k.px.y <= hi.y) st.selection.insert(k.ref);
  } else if (st.drag == CurveEditorState::Drag::Move || st.drag == CurveEditorState::Drag::Tangent) {
    f.doc.endDrag();
    st.dragOriginal.reset();
  }
  st.drag = CurveEditorState::Drag::None;
}

}  // namespace animorph
