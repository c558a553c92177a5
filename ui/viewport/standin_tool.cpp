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
  auto toScreen = [&](const glm::vec3& w, bool& visible) {
    glm::vec3 p = camera.worldToPixel(w, viewport.size);
    visible = p.z > 0.0f && p.z < 1.0f;
    return glm::vec2(p) + viewport.min;
  };
  const int index = selectedStandinSegment(doc);
  const StandinGuideSegment* g = nullptr;
  const auto guides = documentStandinGuides(doc, assets);
  for (const StandinGuides& gs : guides) {
    if (gs.actorId == doc.selection.actorId && index >= 0 && index < int(gs.segments.size())) g = &gs.segments[size_t(index)];
    // Every segment's middle, for automation ("standin/segment/ACTOR/INDEX").
    for (const StandinGuideSegment& s : gs.segments) {
      bool vis = false;
      glm::vec2 p = toScreen(0.5f * (s.a + s.b), vis);
      if (vis && viewport.contains(p)) noteRect("standin/segment/" + gs.actorId + "/" + std::to_string(s.index), p);
    }
  }
  if (!g) {
    endDrags(doc, st);
    return;
  }
  const StandinSegment seg = doc.project().morph.findActor(doc.selection.actorId)->standin.segments[size_t(index)];
  const std::string key = doc.selection.actorId + "/" + std::to_string(index);
  if (!dl) dl = ImGui::GetForegroundDrawList();
  dl->PushClipRect(ImVec2(viewport.min.x, viewport.min.y),
                   ImVec2(viewport.min.x + viewport.size.x, viewport.min.y + viewport.size.y), true);
  const bool mouseFree = !in.blockedByUi && viewport.contains(in.pos);
  const bool busy = st.arrows.dragAxis >= 0 || st.radiusDrag;
  const glm::vec3 mid = 0.5f * (g->a + g->b);

  // End and middle handles: a click puts the translate arrows there.
  struct Handle {
    StandinPart part;
    glm::vec3 world;
    const char* name;
  };
  const Handle handles[3] = {{StandinPart::A, g->a, "standin/handle_a"},
                             {StandinPart::B, g->b, "standin/handle_b"},
                             {StandinPart::Whole, mid, "standin/handle_mid"}};
  for (const Handle& h : handles) {
    bool vis = false;
    glm::vec2 p = toScreen(h.world, vis);
    if (!vis) continue;
    noteRect(h.name, p);
    if (h.part == st.part) continue;  // the arrows' origin is there
    bool hov = mouseFree && !busy && glm::length(in.pos - p) <= kHandlePickPx;
    if (hov) st.hoverHandle = true;
    dl->AddCircle(ImVec2(p.x, p.y), 5.0f, hov ? IM_COL32(255, 235, 140, 255) : IM_COL32(240, 200, 60, 220), 12, 2.0f);
    if (hov && in.pressed[0] && !in.alt) st.part = h.part;
  }

  // Radius handle: on the outline, across the axis as seen on screen.
  bool visA = false, visB = false, visM = false;
  const glm::vec2 pa = toScreen(g->a, visA), pb = toScreen(g->b, visB), pm = toScreen(mid, visM);
  if (visM) {
    glm::vec2 axis = pb - pa;
    glm::vec2 across = glm::length(axis) > 1.0f ? glm::normalize(glm::vec2(-axis.y, axis.x)) : glm::vec2(1.0f, 0.0f);
    if (across.x < 0.0f) across = -across;  // keep the handle on the right side where it can be
    float depth = std::max(1e-4f, glm::dot(mid - camera.eye(), camera.forward()));
    float worldPerPx = 2.0f * depth * std::tan(camera.fovYRad * 0.5f) / std::max(1.0f, viewport.size.y);
    glm::vec2 hp = pm + across * (g->radius / worldPerPx);
    noteRect("standin/radius", hp);
    bool hov = mouseFree && !busy && !st.hoverHandle && glm::length(in.pos - hp) <= kHandlePickPx;
    if (hov) st.hoverHandle = true;
    if (hov && in.pressed[0] && !in.alt) {
      st.radiusDrag = true;
      st.dragStart = seg;
      st.dragGuide = *g;
      st.radiusDirPx = across;
      st.radiusPressPx = in.pos;
      st.radiusWorldPerPx = worldPerPx;
      doc.beginDrag();
    } else if (st.radiusDrag && in.down[0]) {
      float worldR = st.dragGuide.radius + glm::dot(in.pos - st.radiusPressPx, st.radiusDirPx) * st.radiusWorldPerPx;
      StandinSegment next = st.dragStart;
      next.radius = std::max(1e-4f, worldR / std::max(1e-6f, st.dragGuide.nodeScale));
      if (next.radius != seg.radius) {
        executeOrReport(doc,
                        setStandinSegmentCommand(doc.project(), doc.selection.actorId, index, next, "Stand-in radius",
                                                 "standin/radius/" + key),
                        status);
      }
    }
    const bool hi = hov || st.radiusDrag;
    const ImU32 c = hi ? IM_COL32(255, 235, 140, 255) : IM_COL32(120, 230, 255, 240);
    dl->AddLine(ImVec2(pm.x, pm.y), ImVec2(hp.x, hp.y), IM_COL32(120, 230, 255, 140), 1.0f);
    const float r = hi ? 7.0f : 6.0f;
    dl->AddQuadFilled(ImVec2(hp.x, hp.y - r), ImVec2(hp.x + r, hp.y), ImVec2(hp.x, hp.y + r), ImVec2(hp.x - r, hp.y), c);
  }
  if (st.radiusDrag && !in.down[0]) {
    doc.endDrag();
    st.radiusDrag = false;
    char buf[96];
    std::snprintf(buf, sizeof buf, "Stand-in segment %d: radius %.4g m", index,
                  doc.project().morph.findActor(doc.selection.actorId)->standin.segments[size_t(index)].radius);
    status = {buf, false};
  }

  // Translate arrows (world axes) at the active end or the middle.
  const glm::vec3 at = st.part == StandinPart::A ? g->a : st.part == StandinPart::B ? g->b : mid;
  ArrowsLayout l;
  if (layoutTranslateArrows(camera, viewport, at, glm::mat3(1.0f), l)) {
    glm::vec3 offset(0.0f);
    bool canHover = mouseFree && !st.hoverHandle && !st.radiusDrag;
    switch (updateTranslateArrows(st.arrows, l, camera, viewport, in, canHover, "standin/gizmo", offset)) {
      case ArrowEvent::Started:
        st.dragStart = seg;
        st.dragGuide = *g;
        doc.beginDrag();
        break;
      case ArrowEvent::Moved: {
        StandinSegment next = st.dragStart;
        if (st.part != StandinPart::B) next.a = standinWorldToNode(st.dragGuide, st.dragGuide.a + offset);
        if (st.part != StandinPart::A) next.b = standinWorldToNode(st.dragGuide, st.dragGuide.b + offset);
        executeOrReport(doc,
                        setStandinSegmentCommand(doc.project(), doc.selection.actorId, index, next, "Move stand-in segment",
                                                 "standin/move/" + key),
                        status);
        break;
      }
      case ArrowEvent::Ended: doc.endDrag(); break;
      case ArrowEvent::None: break;
    }
    drawTranslateArrows(dl, st.arrows, l);
  }
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
