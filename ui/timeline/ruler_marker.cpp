#include "ui/timeline/ruler_marker.h"

#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {
constexpr float kHandleW = 12.0f, kHandleTop = 22.0f, kHandleBottom = 8.0f;
}  // namespace

void drawRulerMarker(float x, float x0, float x1, float y0, float y1, const char* label, ImU32 color,
                     const std::string& widgetKey) {
  if (x < x0 - 1.0f || x > x1 + 1.0f) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddLine(ImVec2(x, y0), ImVec2(x, y1), (color & ~IM_COL32_A_MASK) | IM_COL32(0, 0, 0, 200), 1.0f);
  dl->AddRectFilled(ImVec2(x + 1.0f, y1 - kHandleTop), ImVec2(x + 1.0f + kHandleW, y1 - kHandleBottom), color, 2.0f);
  dl->AddText(ImVec2(x + 3.0f, y1 - kHandleTop), IM_COL32(20, 20, 20, 255), label);
  noteWidgetRect(widgetKey, {x + 1.0f, y1 - kHandleTop}, {x + 1.0f + kHandleW, y1 - kHandleBottom});
}

bool rulerMarkerHit(glm::vec2 pos, float x, float y1) {
  return pos.y >= y1 - kHandleTop - 2.0f && pos.y <= y1 - kHandleBottom + 2.0f && pos.x >= x - 2.0f &&
         pos.x <= x + kHandleW + 2.0f;
}

}  // namespace animorph
