#pragma once
// Screen rectangles of named widgets as drawn in the last frame, so that
// automation (the headless UI tests, scripted GUI runs) can click a menu item
// or drag a splitter by name instead of by hard-coded coordinates.
#include <map>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace animorph {

struct WidgetRect {
  glm::vec2 min{0.0f}, max{0.0f};
  glm::vec2 center() const { return 0.5f * (min + max); }
};

class WidgetRects {
 public:
  // The rect recorded under key in the frames so far (the latest wins), or nothing.
  std::optional<WidgetRect> find(const std::string& key) const;
  void set(const std::string& key, WidgetRect r) { rects_[key] = r; }
  void clear() { rects_.clear(); }
  const std::map<std::string, WidgetRect>& all() const { return rects_; }

 private:
  std::map<std::string, WidgetRect> rects_;
};

// Makes r the registry that noteWidget writes to (null: none). EditorUI sets
// it for the duration of draw().
void setActiveWidgetRects(WidgetRects* r);
WidgetRects* activeWidgetRects();
// Records ImGui's last item rect under key (no-op without an active registry).
void noteWidget(const std::string& key);
// Records a custom-drawn control's rect (e.g. a handle drawn on a ruler).
void noteWidgetRect(const std::string& key, glm::vec2 min, glm::vec2 max);

}  // namespace animorph
