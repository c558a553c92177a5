#include "ui/viewport/gizmo.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <imgui.h>

#include "ui/common/blob_time.h"
#include "ui/common/command_result.h"
#include "core/doc/blobtree_commands.h"
#include "core/scene/blob_guides.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {
constexpr float kPickPx = 7.0f;
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
  st.hoverHandle = false;
  const Actor* actor = doc.project().findActor(doc.selection.actorId);
  if (!actor || actor->kind != ActorKind::BlobTree || doc.selection.node < 0 || !actor->visible) {
    if (st.arrows.dragAxis >= 0) doc.endDrag();
    st.arrows = {};
    return;
  }
  const BlobTree& tree = actor->blobTree;
  std::vector<ParamAddress> params = gizmoParams(tree, doc.selection.node);
  if (st.actorId != actor->id || st.node != doc.selection.node ||
      std::find(params.begin(), params.end(), st.active) == params.end()) {
    st.actorId = actor->id;
    st.node = doc.selection.node;
    st.active = params.empty() ? ParamAddress{} : params.front();
    if (st.arrows.dragAxis >= 0) doc.endDrag();
    st.arrows = {};
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
    bool hov = mouseFree && st.arrows.dragAxis < 0 && glm::length(in.pos - p) <= kPickPx;
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
  const glm::mat3 J = space.jacobian(local);
  ArrowsLayout l;
  if (!layoutTranslateArrows(camera, viewport, space.toWorld(local), J, l)) {
    dl->PopClipRect();
    return;
  }
  glm::vec3 offset(0.0f);
  switch (updateTranslateArrows(st.arrows, l, camera, viewport, in, mouseFree && !st.hoverHandle, "gizmo", offset)) {
    case ArrowEvent::Started:
      st.dragStartLocal = local;
      st.dragInvJacobian = glm::inverse(J);
      st.dragTimeSec = t;
      doc.beginDrag();
      break;
    case ArrowEvent::Moved: {
      glm::vec3 next = st.dragStartLocal + st.dragInvJacobian * offset;
      executeOrReport(doc,
                      setBlobParamCommand(doc.project(), st.actorId, st.active, st.dragTimeSec, next, false,
                                          "gizmo/" + st.actorId + "/" + std::to_string(st.node)),
                      status);
      break;
    }
    case ArrowEvent::Ended: doc.endDrag(); break;
    case ArrowEvent::None: break;
  }
  drawTranslateArrows(dl, st.arrows, l);
  dl->PopClipRect();
}

}  // namespace animorph
