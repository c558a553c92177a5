#include "ui/viewport/translate_arrows.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <imgui.h>

#include "ui/widgets/widget_rects.h"

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

bool layoutTranslateArrows(const OrbitCamera& camera, const ViewportRect& viewport, const glm::vec3& origin,
                           const glm::mat3& dirs, ArrowsLayout& out) {
  auto toScreen = [&](const glm::vec3& w, bool& visible) {
    glm::vec3 p = camera.worldToPixel(w, viewport.size);
    visible = p.z > 0.0f && p.z < 1.0f;
    return glm::vec2(p) + viewport.min;
  };
  bool vis = false;
  out.origin = origin;
  out.originPx = toScreen(origin, vis);
  if (!vis) return false;
  float depth = std::max(1e-4f, glm::dot(origin - camera.eye(), camera.forward()));
  out.worldPerPx = 2.0f * depth * std::tan(camera.fovYRad * 0.5f) / std::max(1.0f, viewport.size.y);
  for (int k = 0; k < 3; ++k) {
    glm::vec3 d = dirs[k];
    out.dirs[k] = glm::length(d) > 1e-9f ? glm::normalize(d) : glm::vec3(k == 0, k == 1, k == 2);
    out.tipsPx[k] = toScreen(origin + out.dirs[k] * (kArrowPx * out.worldPerPx), out.tipVisible[k]);
  }
  return true;
}

ArrowEvent updateTranslateArrows(TranslateArrows& st, const ArrowsLayout& l, const OrbitCamera& camera,
                                 const ViewportRect& viewport, const PointerInput& in, bool canHover,
                                 const char* widgetPrefix, glm::vec3& offset) {
  st.hoverAxis = -1;
  for (int k = 0; k < 3; ++k)
    if (canHover && st.dragAxis < 0 && l.tipVisible[k] && distToSegment(in.pos, l.originPx, l.tipsPx[k]) <= kPickPx)
      st.hoverAxis = k;
  if (WidgetRects* r = activeWidgetRects()) {
    const std::string p = widgetPrefix;
    r->set(p + "/origin", {l.originPx - glm::vec2(2.0f), l.originPx + glm::vec2(2.0f)});
    static const char* kNames[3] = {"/x", "/y", "/z"};
    for (int k = 0; k < 3; ++k) {
      glm::vec2 m = l.originPx + (l.tipsPx[k] - l.originPx) * 0.8f;
      r->set(p + kNames[k], {m - glm::vec2(2.0f), m + glm::vec2(2.0f)});
    }
  }
  Ray ray = camera.rayThroughPixel(in.pos.x - viewport.min.x, in.pos.y - viewport.min.y, viewport.size);
  offset = glm::vec3(0.0f);
  if (st.dragAxis < 0 && st.hoverAxis >= 0 && in.pressed[0] && !in.alt) {
    float s = 0.0f;
    if (closestOnLine(l.origin, l.dirs[st.hoverAxis], ray, s)) {
      st.dragAxis = st.hoverAxis;
      st.dragOrigin = l.origin;
      st.dragDir = l.dirs[st.dragAxis];
      st.dragStartS = s;
      return ArrowEvent::Started;
    }
  } else if (st.dragAxis >= 0 && in.down[0]) {
    float s = 0.0f;
    if (!closestOnLine(st.dragOrigin, st.dragDir, ray, s)) return ArrowEvent::None;
    // Clamp absurd jumps when the axis points almost at the camera.
    float maxMove = 1000.0f * kArrowPx * l.worldPerPx;
    offset = st.dragDir * std::clamp(s - st.dragStartS, -maxMove, maxMove);
    return ArrowEvent::Moved;
  }
  if (st.dragAxis >= 0 && !in.down[0]) {
    st.dragAxis = -1;
    return ArrowEvent::Ended;
  }
  return ArrowEvent::None;
}

void drawTranslateArrows(ImDrawList* dl, const TranslateArrows& st, const ArrowsLayout& l) {
  static const ImU32 kColors[3] = {IM_COL32(235, 70, 70, 255), IM_COL32(90, 210, 80, 255), IM_COL32(80, 130, 255, 255)};
  const glm::vec2 o = l.originPx;
  for (int k = 0; k < 3; ++k) {
    bool hi = st.hoverAxis == k || st.dragAxis == k;
    ImU32 c = hi ? IM_COL32(255, 235, 120, 255) : kColors[k];
    const glm::vec2 tip = l.tipsPx[k];
    dl->AddLine(ImVec2(o.x, o.y), ImVec2(tip.x, tip.y), c, hi ? 4.0f : 3.0f);
    glm::vec2 d = tip - o;
    float len = glm::length(d);
    if (len > 1.0f) {
      d /= len;
      glm::vec2 n(-d.y, d.x);
      glm::vec2 b = tip - d * 12.0f;
      dl->AddTriangleFilled(ImVec2(tip.x + d.x * 4.0f, tip.y + d.y * 4.0f), ImVec2(b.x + n.x * 6.0f, b.y + n.y * 6.0f),
                            ImVec2(b.x - n.x * 6.0f, b.y - n.y * 6.0f), c);
    }
  }
  dl->AddCircleFilled(ImVec2(o.x, o.y), 4.0f, IM_COL32(240, 240, 240, 255));
}

}  // namespace animorph
