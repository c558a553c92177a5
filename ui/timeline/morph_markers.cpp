#include "ui/timeline/morph_markers.h"

#include <imgui.h>

#include <algorithm>
#include <string>

#include "core/doc/project_commands.h"
#include "ui/timeline/ruler_marker.h"

namespace animorph {

int morphMarkerAt(const Document& doc, glm::vec2 pos, float x0, float x1, float /*y0*/, float y1, double viewStart,
                  double viewEnd) {
  const MorphSetup& m = doc.project().morph;
  if (!m.enabled() || viewEnd <= viewStart) return -1;
  const int marks[4] = {m.markers.a, m.markers.b, m.markers.c, m.markers.d};
  // Later markers first: when handles overlap, the one drawn on top wins.
  for (int i = 3; i >= 0; --i)
    if (rulerMarkerHit(pos, rulerX(marks[i], x0, x1, viewStart, viewEnd), y1)) return i;
  return -1;
}

void moveMorphMarker(Document& doc, int index, int frame) {
  const Project& p = doc.project();
  MorphMarkers mk = p.morph.markers;
  int* v[4] = {&mk.a, &mk.b, &mk.c, &mk.d};
  const int lo = index > 0 ? *v[index - 1] : p.timeline.frameStart;
  const int hi = index < 3 ? *v[index + 1] : p.timeline.frameEnd;
  frame = std::clamp(frame, lo, std::max(lo, hi));
  if (*v[index] == frame) return;
  *v[index] = frame;
  static const char* names[4] = {"A", "B", "C", "D"};
  doc.execute(setMorphField(p, &MorphSetup::markers, mk, std::string("Move morph marker ") + names[index],
                            "morph/markers"));
}

void drawMorphMarkers(const Document& doc, float x0, float x1, float y0, float y1, double viewStart, double viewEnd) {
  const MorphSetup& m = doc.project().morph;
  if (!m.enabled() || viewEnd <= viewStart) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  auto xOf = [&](int f) { return rulerX(f, x0, x1, viewStart, viewEnd); };
  // The stages as coloured bands along the bottom of the ruler.
  const int marks[4] = {m.markers.a, m.markers.b, m.markers.c, m.markers.d};
  const ImU32 bands[3] = {IM_COL32(200, 120, 60, 110), IM_COL32(150, 90, 200, 110), IM_COL32(60, 150, 200, 110)};
  for (int i = 0; i < 3; ++i)
    dl->AddRectFilled(ImVec2(std::max(x0, xOf(marks[i])), y1 - 6.0f), ImVec2(std::min(x1, xOf(marks[i + 1])), y1),
                      bands[i]);
  const char* names[4] = {"A", "B", "C", "D"};
  for (int i = 0; i < 4; ++i)
    drawRulerMarker(xOf(marks[i]), x0, x1, y0, y1, names[i], IM_COL32(240, 170, 70, 230),
                    std::string("timeline/marker/") + names[i]);
}

}  // namespace animorph
