#include "gizmo.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <imgui.h>

#include "blob_inspector.h"
#include "doc/blobtree_commands.h"
#include "scene/blob_guides.h"
#include "widget_rects.h"

namespace animorph {

namespace {

constexpr float kArrowPx = 80.0f;
constexpr float kPickPx = 7.0f;

float distToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  glm::vec2 ab = b - a;
  float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

// Parameter along the line (o, d) of its point closest to the ray; false when they are parallel.
bool closestOnLine(const glm::vec3& o, const glm::vec3& d, const Ray& ray, float& s) {
  glm::vec3 w0 = o - ray.origin;
  float b = glm::dot(d, ray.direction);
  float denom = glm::dot(d, d) * glm::dot(ray.direction, ray.direction) - b * b;
  if (std::abs(denom) < 1e-6f) return false;
  s = (b * glm::dot(ray.direction, w0) - glm::dot(ray.direction, ray.direction) * glm::dot(d, w0)) / denom;
  return true;
}

}  // namespace

std::vector<ParamAddress> gizmoParams(const BlobTree& tree, int nodeId) {
  std::vector<ParamAddress> out;
  const BlobNode* n = tree.find(nodeId);
  if (!n) return out;
  const auto& specs = nodeTypeInfo(n->type).params;
  for (size_t i = 0; i < specs.size(); ++i) {
    const char* name = specs[i].name;
    bool position = std::strcmp(name, "center") == 0 || std::strcmp(name, "a") == 0 || std::strcmp(name, "b") == 0 ||
                    std::strcmp(name, "c") == 0 || std::strcmp(name, "translation") == 0;
    if (specs[i].kind == ParamKind::Vec3 && position) out.push_back({nodeId, int(i), -1});
    if (specs[i].kind == ParamKind::Vec3List) {
      const auto& pts = std::get<ControlPoints>(n->params[i]);
      for (size_t k = 0; k < pts.size(); ++k) out.push_back({nodeId, int(i), int(k)});
    }
  }
  return out;
}

void drawGizmo(Document& doc, const OrbitCamera& camera, const ViewportRect& viewport, const PointerInput& in,
               GizmoState& st, StatusMessage& status, ImDrawList* dl) {
  st.hoverAxis = -1;
  st.hoverHandle = false;
  const Actor* actor = doc.project().findActor(doc.selection.actorId);
  if (!actor || actor->kind != ActorKind::BlobTree || doc.selection.node < 0 || !actor->visible) {
    if (st.dragAxis >= 0) doc.endDrag();
    st.dragAxis = -1;
    return;
  }
  const BlobTree& tree = actor->blobTree;
  std::vector<ParamAddress> params = gizmoParams(tree, doc.selection.node);
  if (st.actorId != actor->id || st.node != doc.selection.node ||
      std::find(params.begin(), params.end(), st.active) == params.end()) {
    st.actorId = actor->id;
    st.node = doc.selection.node;
    st.active = params.empty() ? ParamAddress{} : params.front();
    if (st.dragAxis >= 0) doc.endDrag();
    st.dragAxis = -1;
  }
  if (params.empty()) return;
  const double t = blobTreeTimeNow(doc, *actor);
  NodeSpace space;
  if (!nodeSpace(tree, st.node, t, actor->transform.matrix(), space)) return;

  auto toScreen = [&](const glm::vec3& w, bool& visible) {
    glm::vec3 p = camera.worldToPixel(w, viewport.size);
    visible = p.z > 0.0f && p.z < 1.0f;
    return glm::vec2(p) + viewport.min;
  };
  if (!dl) dl = ImGui::GetForegroundDrawList();
  dl->PushClipRect(ImVec2(viewport.min.x, viewport.min.y),
                   ImVec2(viewport.min.x + viewport.size.x, viewport.min.y + viewport.size.y), true);
  const bool mouseFree = !in.blockedByUi && viewport.contains(in.pos);

  // The node's other positions: small circles; a click moves the gizmo there.
  ParamAddress clicked;
  bool switchTo = false;
  for (const auto& a : params) {
    ParamSample v;
    if (!sampleParam(tree, a, t, v) || a == st.active) continue;
    bool vis = false;
    glm::vec2 p = toScreen(space.toWorld(std::get<glm::vec3>(v)), vis);
    if (!vis) continue;
    bool hov = mouseFree && st.dragAxis < 0 && glm::length(in.pos - p) <= kPickPx;
    if (hov) st.hoverHandle = true;
    dl->AddCircle(ImVec2(p.x, p.y), 5.0f, hov ? IM_COL32(255, 235, 140, 255) : IM_COL32(240, 200, 60, 220), 12, 2.0f);
    if (hov && in.pressed[0] && !in.alt) {
      clicked = a;
      switchTo = true;
    }
  }
  if (switchTo) st.active = clicked;

  ParamSample value;
  if (!sampleParam(tree, st.active, t, value)) {
    dl->PopClipRect();
    return;
  }
  const glm::vec3 local = std::get<glm::vec3>(value);
  const glm::vec3 origin = space.toWorld(local);
  const glm::mat3 J = space.jacobian(local);
  bool vis = false;
  const glm::vec2 o = toScreen(origin, vis);
  if (!vis) {
    dl->PopClipRect();
    return;
  }
  // World length that appears kArrowPx long at the gizmo's depth.
  float depth = std::max(1e-4f, glm::dot(origin - camera.eye(), camera.forward()));
  float worldPerPx = 2.0f * depth * std::tan(camera.fovYRad * 0.5f) / std::max(1.0f, viewport.size.y);
  glm::vec3 dirs[3];
  glm::vec2 tips[3];
  for (int k = 0; k < 3; ++k) {
    glm::vec3 d = J[k];
    dirs[k] = glm::length(d) > 1e-9f ? glm::normalize(d) : glm::vec3(k == 0, k == 1, k == 2);
    bool tv = false;
    tips[k] = toScreen(origin + dirs[k] * (kArrowPx * worldPerPx), tv);
    if (mouseFree && st.dragAxis < 0 && !st.hoverHandle && tv && distToSegment(in.pos, o, tips[k]) <= kPickPx)
      st.hoverAxis = k;
  }
  if (WidgetRects* r = activeWidgetRects()) r->set("gizmo/origin", {o - glm::vec2(2.0f), o + glm::vec2(2.0f)});
  if (WidgetRects* r = activeWidgetRects())
    for (int k = 0; k < 3; ++k) {
      glm::vec2 m = o + (tips[k] - o) * 0.8f;
      static const char* kNames[3] = {"gizmo/x", "gizmo/y", "gizmo/z"};
      r->set(kNames[k], {m - glm::vec2(2.0f), m + glm::vec2(2.0f)});
    }

  // Start, continue and end a drag.
  Ray ray = camera.rayThroughPixel(in.pos.x - viewport.min.x, in.pos.y - viewport.min.y, viewport.size);
  if (st.dragAxis < 0 && st.hoverAxis >= 0 && in.pressed[0] && !in.alt) {
    float s = 0.0f;
    if (closestOnLine(origin, dirs[st.hoverAxis], ray, s)) {
      st.dragAxis = st.hoverAxis;
      st.dragOrigin = origin;
      st.dragDir = dirs[st.dragAxis];
      st.dragStartS = s;
      st.dragStartLocal = local;
      st.dragInvJacobian = glm::inverse(J);
      st.dragTimeSec = t;
      doc.beginDrag();
    }
  } else if (st.dragAxis >= 0 && in.down[0]) {
    float s = 0.0f;
    if (closestOnLine(st.dragOrigin, st.dragDir, ray, s)) {
      // Clamp absurd jumps when the axis points almost at the camera.
      float maxMove = 1000.0f * kArrowPx * worldPerPx;
      float ds = std::clamp(s - st.dragStartS, -maxMove, maxMove);
      glm::vec3 next = st.dragStartLocal + st.dragInvJacobian * (st.dragDir * ds);
      auto cmd = setBlobParamCommand(doc.project(), st.actorId, st.active, st.dragTimeSec, next, false,
                                     "gizmo/" + st.actorId + "/" + std::to_string(st.node));
      if (cmd) doc.execute(std::move(*cmd));
      else status = {cmd.error(), true};
    }
  }
  if (st.dragAxis >= 0 && !in.down[0]) {
    doc.endDrag();
    st.dragAxis = -1;
  }

  static const ImU32 kColors[3] = {IM_COL32(235, 70, 70, 255), IM_COL32(90, 210, 80, 255), IM_COL32(80, 130, 255, 255)};
  for (int k = 0; k < 3; ++k) {
    bool hi = st.hoverAxis == k || st.dragAxis == k;
    ImU32 c = hi ? IM_COL32(255, 235, 120, 255) : kColors[k];
    dl->AddLine(ImVec2(o.x, o.y), ImVec2(tips[k].x, tips[k].y), c, hi ? 4.0f : 3.0f);
    glm::vec2 d = tips[k] - o;
    float len = glm::length(d);
    if (len > 1.0f) {
      d /= len;
      glm::vec2 n(-d.y, d.x);
      glm::vec2 b = tips[k] - d * 12.0f;
      dl->AddTriangleFilled(ImVec2(tips[k].x + d.x * 4.0f, tips[k].y + d.y * 4.0f), ImVec2(b.x + n.x * 6.0f, b.y + n.y * 6.0f),
                            ImVec2(b.x - n.x * 6.0f, b.y - n.y * 6.0f), c);
    }
  }
  dl->AddCircleFilled(ImVec2(o.x, o.y), 4.0f, IM_COL32(240, 240, 240, 255));
  dl->PopClipRect();
}

}  // namespace animorph
