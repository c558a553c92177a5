#include "ui/widgets/widget_rects.h"

#include <imgui.h>

namespace animorph {
namespace {
WidgetRects* g_active = nullptr;
}

std::optional<WidgetRect> WidgetRects::find(const std::string& key) const {
  auto it = rects_.find(key);
  if (it == rects_.end()) return std::nullopt;
  return it->second;
}

void setActiveWidgetRects(WidgetRects* r) { g_active = r; }
WidgetRects* activeWidgetRects() { return g_active; }

void noteWidget(const std::string& key) {
  if (!g_active) return;
  ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  g_active->set(key, {{a.x, a.y}, {b.x, b.y}});
}

void noteWidgetRect(const std::string& key, glm::vec2 min, glm::vec2 max) {
  if (g_active) g_active->set(key, {min, max});
}

}  // namespace animorph
