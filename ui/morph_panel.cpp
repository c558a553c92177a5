#include "morph_panel.h"

#include <imgui.h>

#include <algorithm>

#include "widget_rects.h"

namespace animorph {
namespace {

// A command that sets one field of the project's morph.
template <class T>
std::unique_ptr<Command> setMorphField(const Project& p, T MorphSetup::*field, T value, std::string label,
                                       std::string mergeKey = {}) {
  return std::make_unique<SetValueCommand<T>>(
      std::move(label), [field](Project& proj) -> T* { return &(proj.morph.*field); }, p.morph.*field,
      std::move(value), std::move(mergeKey));
}

}  // namespace

void drawMorphSettings(Document& doc, DragMerge& drag) {
  const MorphSetup m = doc.project().morph;  // copy: commands below change the project
  ImGui::TextUnformatted("Morph");
  ImGui::Separator();
  ImGui::Text("%s  ->  %s", m.sourceActorId.c_str(), m.targetActorId.c_str());
  ImGui::PushItemWidth(-90.0f);

  // Markers A..D in frames, kept in order: A <= B <= C <= D.
  MorphMarkers mk = m.markers;
  int v[4] = {mk.a, mk.b, mk.c, mk.d};
  bool changed = ImGui::DragInt4("Markers", v, 0.2f, doc.project().timeline.frameStart,
                                 doc.project().timeline.frameEnd);
  noteWidget("morph/markers");
  drag.begin(doc);
  if (changed) {
    for (int i = 1; i < 4; ++i) v[i] = std::max(v[i], v[i - 1]);
    MorphMarkers next{v[0], v[1], v[2], v[3]};
    if (!(next == mk)) doc.execute(setMorphField(doc.project(), &MorphSetup::markers, next, "Move morph markers", "morph/markers"));
  }
  drag.end(doc);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A: the source starts to collapse; B: implicit morph starts;\nC: the target starts to grow; D: the target plays");

  int method = static_cast<int>(m.method);
  const char* methods[] = {"Interpolation", "Space-time blending"};
  if (ImGui::Combo("Method", &method, methods, 2))
    doc.execute(setMorphField(doc.project(), &MorphSetup::method, static_cast<MorphMethod>(method), "Set morph method"));
  noteWidget("morph/method");

  if (m.method == MorphMethod::SpaceTime) {
    SpaceTimeParams st = m.spaceTime;
    bool c = false;
    c |= ImGui::DragFloat("Time scale", &st.timeScale, 0.01f, 0.01f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a0 amount", &st.a0, 0.01f, 0.0f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a1 source", &st.a1, 0.05f, 0.01f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a2 target", &st.a2, 0.05f, 0.01f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a3 time", &st.a3, 0.001f, 0.001f, 10.0f);
    drag.begin(doc);
    if (c && !(st == m.spaceTime))
      doc.execute(setMorphField(doc.project(), &MorphSetup::spaceTime, st, "Set space-time blending", "morph/spacetime"));
    drag.end(doc);
  }
  float shift = m.weightMapShift;
  bool c = ImGui::SliderFloat("Paint shift", &shift, 0.0f, 1.0f, "%.2f");
  drag.begin(doc);
  if (c) doc.execute(setMorphField(doc.project(), &MorphSetup::weightMapShift, shift, "Set weight-map shift", "morph/shift"));
  drag.end(doc);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("How much earlier painted vertices start their transition (fraction of the transition)");

  MorphCrossFade fade = m.crossFade;
  bool fc = ImGui::Checkbox("Cross-fade at B, C", &fade.enabled);
  noteWidget("morph/crossfade");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Around markers B and C, draw the mesh and the implicit surface dithered with\n"
                      "complementary opacity (hides the switch on coarse meshes)");
  if (fade.enabled) {
    fc |= ImGui::SliderInt("Fade width", &fade.widthFrames, 1, 24, "%d frames");
    drag.begin(doc);
  }
  if (fc && !(fade == m.crossFade))
    doc.execute(setMorphField(doc.project(), &MorphSetup::crossFade, fade, "Set morph cross-fade", "morph/crossfade"));
  drag.end(doc);
  ImGui::PopItemWidth();
}

namespace {
// Handle of a marker on the ruler: a small flag above the stage bands.
constexpr float kHandleW = 12.0f, kHandleTop = 22.0f, kHandleBottom = 8.0f;
float markerX(int frame, float x0, float x1, double viewStart, double viewEnd) {
  return static_cast<float>(x0 + (frame - viewStart) * (x1 - x0) / (viewEnd - viewStart));
}
}  // namespace

int morphMarkerAt(const Document& doc, glm::vec2 pos, float x0, float x1, float /*y0*/, float y1, double viewStart,
                  double viewEnd) {
  const MorphSetup& m = doc.project().morph;
  if (!m.enabled() || viewEnd <= viewStart) return -1;
  if (pos.y < y1 - kHandleTop - 2.0f || pos.y > y1 - kHandleBottom + 2.0f) return -1;
  const int marks[4] = {m.markers.a, m.markers.b, m.markers.c, m.markers.d};
  // Later markers first: when handles overlap, the one drawn on top wins.
  for (int i = 3; i >= 0; --i) {
    float x = markerX(marks[i], x0, x1, viewStart, viewEnd);
    if (pos.x >= x - 2.0f && pos.x <= x + kHandleW + 2.0f) return i;
  }
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
  auto xOf = [&](int f) { return static_cast<float>(x0 + (f - viewStart) * (x1 - x0) / (viewEnd - viewStart)); };
  // The stages as coloured bands along the bottom of the ruler.
  const int marks[4] = {m.markers.a, m.markers.b, m.markers.c, m.markers.d};
  const ImU32 bands[3] = {IM_COL32(200, 120, 60, 110), IM_COL32(150, 90, 200, 110), IM_COL32(60, 150, 200, 110)};
  for (int i = 0; i < 3; ++i)
    dl->AddRectFilled(ImVec2(std::max(x0, xOf(marks[i])), y1 - 6.0f), ImVec2(std::min(x1, xOf(marks[i + 1])), y1),
                      bands[i]);
  const char* names[4] = {"A", "B", "C", "D"};
  for (int i = 0; i < 4; ++i) {
    float x = xOf(marks[i]);
    if (x < x0 - 1.0f || x > x1 + 1.0f) continue;
    dl->AddLine(ImVec2(x, y0), ImVec2(x, y1), IM_COL32(240, 170, 70, 200), 1.0f);
    dl->AddRectFilled(ImVec2(x + 1.0f, y1 - kHandleTop), ImVec2(x + 1.0f + kHandleW, y1 - kHandleBottom),
                      IM_COL32(240, 170, 70, 230), 2.0f);
    dl->AddText(ImVec2(x + 3.0f, y1 - kHandleTop), IM_COL32(20, 20, 20, 255), names[i]);
    noteWidgetRect(std::string("timeline/marker/") + names[i], {x + 1.0f, y1 - kHandleTop},
                   {x + 1.0f + kHandleW, y1 - kHandleBottom});
  }
}

}  // namespace animorph
