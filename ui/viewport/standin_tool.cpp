#include "ui/viewport/standin_tool.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "ui/common/command_result.h"
#include "core/doc/standin_commands.h"
#include "editor/standin_pick.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

constexpr float kHandlePickPx = 7.0f;

void endDrags(Document& doc, StandinToolState& st) {
  if (st.arrows.dragAxis >= 0 || st.radiusDrag) doc.endDrag();
  st.arrows = {};
  st.radiusDrag = false;
}

void noteRect(const std::string& key, glm::vec2 p) {
  if (WidgetRects* r = activeWidgetRects()) r->set(key, {p - glm::vec2(2.0f), p + glm::vec2(2.0f)});
}

glm::vec2 toScreen(const OrbitCamera& camera, const ViewportRect& viewport, const glm::vec3& w, bool& visible) {
  glm::vec3 p = camera.worldToPixel(w, viewport.size);
  visible = p.z > 0.0f && p.z < 1.0f;
  return glm::vec2(p) + viewport.min;
}

// Notes every segment's middle for automation ("standin/segment/ACTOR/INDEX"); returns the guide of
// the selected segment (index in the selected actor), null when none is selected or shown.
const StandinGuideSegment* noteSegmentsFindSelected(const Document& doc, const std::vector<StandinGuides>& guides,
                                                    int index, const OrbitCamera& camera,
                                                    const ViewportRect& viewport) {
  const StandinGuideSegment* g = nullptr;
  for (const StandinGuides& gs : guides) {
    if (gs.actorId == doc.selection.actorId && index >= 0 && index < int(gs.segments.size())) g = &gs.segments[size_t(index)];
    for (const StandinGuideSegment& s : gs.segments) {
      bool vis = false;
      glm::vec2 p = toScreen(camera, viewport, 0.5f * (s.a + s.b), vis);
      if (vis && viewport.contains(p)) noteRect("standin/segment/" + gs.actorId + "/" + std::to_string(s.index), p);
    }
  }
  return g;
}

// The tool's frame over the selected segment.
struct ToolFrame {
  Document& doc;
  const OrbitCamera& camera;
  const ViewportRect& viewport;
  const PointerInput& in;
  StandinToolState& st;
  StatusMessage& status;
  ImDrawList* dl;
  const StandinGuideSegment& g;  // the selected segment in world units
  int index;                     // its index in the selected actor's stand-in
  StandinSegment seg;            // as it is now
  std::string key;               // "ACTOR/INDEX", the drags' merge keys
  bool mouseFree;                // over the viewport, not over a panel
  bool busy;                     // a drag was running when the frame began
  glm::vec3 mid;                 // the segment's middle (world)

  glm::vec2 screen(const glm::vec3& w, bool& visible) const { return toScreen(camera, viewport, w, visible); }
};

// End and middle handles: a click puts the translate arrows there.
void drawEndHandles(ToolFrame& f) {
  struct Handle {
    StandinPart part;
    glm::vec3 world;
    const char* name;
  };
  const Handle handles[3] = {{StandinPart::A, f.g.a, "standin/handle_a"},
                             {StandinPart::B, f.g.b, "standin/handle_b"},
                             {StandinPart::Whole, f.mid, "standin/handle_mid"}};
  for (const Handle& h : handles) {
    bool vis = false;
    glm::vec2 p = f.screen(h.world, vis);
    if (!vis) continue;
    noteRect(h.name, p);
    if (h.part == f.st.part) continue;  // the arrows' origin is there
    bool hov = f.mouseFree && !f.busy && glm::length(f.in.pos - p) <= kHandlePickPx;
    if (hov) f.st.hoverHandle = true;
    f.dl->AddCircle(ImVec2(p.x, p.y), 5.0f, hov ? IM_COL32(255, 235, 140, 255) : IM_COL32(240, 200, 60, 220), 12, 2.0f);
    if (hov && f.in.pressed[0] && !f.in.alt) f.st.part = h.part;
  }
}

// The radius drag under way: the segment's radius follows the pointer across the axis.
void dragRadius(ToolFrame& f) {
  StandinToolState& st = f.st;
  float worldR = st.dragGuide.radius + glm::dot(f.in.pos - st.radiusPressPx, st.radiusDirPx) * st.radiusWorldPerPx;
  StandinSegment next = st.dragStart;
  next.radius = std::max(1e-4f, worldR / std::max(1e-6f, st.dragGuide.nodeScale));
  if (next.radius != f.seg.radius) {
    executeOrReport(f.doc,
                    setStandinSegmentCommand(f.doc.project(), f.doc.selection.actorId, f.index, next, "Stand-in radius",
                                             "standin/radius/" + f.key),
                    f.status);
  }
}

// Radius handle: on the outline, across the axis as seen on screen. A drag on it is one undo step;
// its end says the new radius in the status bar.
void drawRadiusHandle(ToolFrame& f) {
  StandinToolState& st = f.st;
  bool visA = false, visB = false, visM = false;
  const glm::vec2 pa = f.screen(f.g.a, visA), pb = f.screen(f.g.b, visB), pm = f.screen(f.mid, visM);
  if (visM) {
    glm::vec2 axis = pb - pa;
    glm::vec2 across = glm::length(axis) > 1.0f ? glm::normalize(glm::vec2(-axis.y, axis.x)) : glm::vec2(1.0f, 0.0f);
    if (across.x < 0.0f) across = -across;  // keep the handle on the right side where it can be
    float depth = std::max(1e-4f, glm::dot(f.mid - f.camera.eye(), f.camera.forward()));
    float worldPerPx = 2.0f * depth * std::tan(f.camera.fovYRad * 0.5f) / std::max(1.0f, f.viewport.size.y);
    glm::vec2 hp = pm + across * (f.g.radius / worldPerPx);
    noteRect("standin/radius", hp);
    bool hov = f.mouseFree && !f.busy && !st.hoverHandle && glm::length(f.in.pos - hp) <= kHandlePickPx;
    if (hov) st.hoverHandle = true;
    if (hov && f.in.pressed[0] && !f.in.alt) {
      st.radiusDrag = true;
      st.dragStart = f.seg;
      st.dragGuide = f.g;
      st.radiusDirPx = across;
      st.radiusPressPx = f.in.pos;
      st.radiusWorldPerPx = worldPerPx;
      f.doc.beginDrag();
    } else if (st.radiusDrag && f.in.down[0]) {
      dragRadius(f);
    }
    const bool hi = hov || st.radiusDrag;
    const ImU32 c = hi ? IM_COL32(255, 235, 140, 255) : IM_COL32(120, 230, 255, 240);
    f.dl->AddLine(ImVec2(pm.x, pm.y), ImVec2(hp.x, hp.y), IM_COL32(120, 230, 255, 140), 1.0f);
    const float r = hi ? 7.0f : 6.0f;
    f.dl->AddQuadFilled(ImVec2(hp.x, hp.y - r), ImVec2(hp.x + r, hp.y), ImVec2(hp.x, hp.y + r), ImVec2(hp.x - r, hp.y), c);
  }
  if (st.radiusDrag && !f.in.down[0]) {
    f.doc.endDrag();
    st.radiusDrag = false;
    char buf[96];
    std::snprintf(buf, sizeof buf, "Stand-in segment %d: radius %.4g m", f.index,
                  f.doc.project().morph.findActor(f.doc.selection.actorId)->standin.segments[size_t(f.index)].radius);
    f.status = {buf, false};
  }
}

// Translate arrows (world axes) at the active end or the middle; a drag moves that end (or the
// whole segment) as one undo step.
void driveTranslateArrows(ToolFrame& f) {
  StandinToolState& st = f.st;
  const glm::vec3 at = st.part == StandinPart::A ? f.g.a : st.part == StandinPart::B ? f.g.b : f.mid;
  ArrowsLayout l;
  if (!layoutTranslateArrows(f.camera, f.viewport, at, glm::mat3(1.0f), l)) return;
  glm::vec3 offset(0.0f);
  bool canHover = f.mouseFree && !st.hoverHandle && !st.radiusDrag;
  switch (updateTranslateArrows(st.arrows, l, f.camera, f.viewport, f.in, canHover, "standin/gizmo", offset)) {
    case ArrowEvent::Started:
      st.dragStart = f.seg;
      st.dragGuide = f.g;
      f.doc.beginDrag();
      break;
    case ArrowEvent::Moved: {
      StandinSegment next = st.dragStart;
      if (st.part != StandinPart::B) next.a = standinWorldToNode(st.dragGuide, st.dragGuide.a + offset);
      if (st.part != StandinPart::A) next.b = standinWorldToNode(st.dragGuide, st.dragGuide.b + offset);
      executeOrReport(f.doc,
                      setStandinSegmentCommand(f.doc.project(), f.doc.selection.actorId, f.index, next,
                                               "Move stand-in segment", "standin/move/" + f.key),
                      f.status);
      break;
    }
    case ArrowEvent::Ended: f.doc.endDrag(); break;
    case ArrowEvent::None: break;
  }
  drawTranslateArrows(f.dl, st.arrows, l);
}

}  // namespace

int selectedStandinSegment(const Document& doc) {
  const Selection& sel = doc.selection;
  if (sel.segment < 0 || sel.actorId.empty() || sel.node >= 0) return -1;
  const ActorMorph* am = doc.project().morph.findActor(sel.actorId);
  if (!am || sel.segment >= int(am->standin.segments.size())) return -1;
  return sel.segment;
}

double documentTimeSec(const Document& doc) {
  const Timeline& tl = doc.project().timeline;
  return tl.currentTimeSec();
}

std::vector<StandinGuides> documentStandinGuides(const Document& doc, AssetCache& assets) {
  return projectStandinGuides(doc.project(), doc.baseDir(), assets, documentTimeSec(doc), doc.selection.actorId);
}

void drawStandinTool(Document& doc, AssetCache& assets, const OrbitCamera& camera, const ViewportRect& viewport,
                     const PointerInput& in, StandinToolState& st, StatusMessage& status, ImDrawList* dl) {
  st.hoverHandle = false;
  const int index = selectedStandinSegment(doc);
  const auto guides = documentStandinGuides(doc, assets);
  const StandinGuideSegment* g = noteSegmentsFindSelected(doc, guides, index, camera, viewport);
  if (!g) {
    endDrags(doc, st);
    return;
  }
  if (!dl) dl = ImGui::GetForegroundDrawList();
  ToolFrame f{doc, camera, viewport, in, st, status, dl, *g, index,
              doc.project().morph.findActor(doc.selection.actorId)->standin.segments[size_t(index)],
              doc.selection.actorId + "/" + std::to_string(index),
              !in.blockedByUi && viewport.contains(in.pos),
              st.arrows.dragAxis >= 0 || st.radiusDrag,
              0.5f * (g->a + g->b)};
  dl->PushClipRect(ImVec2(viewport.min.x, viewport.min.y),
                   ImVec2(viewport.min.x + viewport.size.x, viewport.min.y + viewport.size.y), true);
  drawEndHandles(f);
  drawRadiusHandle(f);
  driveTranslateArrows(f);
  dl->PopClipRect();
}

bool pickStandinClick(Document& doc, AssetCache& assets, const OrbitCamera& camera, const ViewportRect& viewport,
                      glm::vec2 windowPos, StandinToolState& st) {
  auto hit = pickStandinSegment(documentStandinGuides(doc, assets), camera, viewport.size, windowPos - viewport.min);
  if (!hit) {
    doc.selection.segment = -1;
    return false;
  }
  if (doc.selection.actorId != hit->actorId || doc.selection.segment != hit->segment) st.part = StandinPart::Whole;
  st.scrollList = true;
  doc.selection = Selection{hit->actorId, -1, hit->segment};
  return true;
}

}  // namespace animorph
