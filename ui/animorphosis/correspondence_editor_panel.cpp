// The correspondence editor: the source and target trees side by side, the correspondence graph as
// wires between their rows (animorphosis_panel.h). This file runs a frame of the window; the parts
// are in correspondence_editor_{draw,edit,select}.cpp and correspondence_chain_tab.cpp.
#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "ui/animorphosis/animorphosis_panel.h"
#include "ui/animorphosis/correspondence_editor_intern.h"
#include "ui/widgets/tool_window.h"
#include "ui/widgets/view_zoom.h"

namespace animorph {

namespace {

constexpr float kMinZoom = 0.15f, kMaxZoom = 4.0f;

// The layout in content units (pixels at zoom 1): the source's column, the gap the wires cross,
// the target's; and the trees' visible rows.
void layOutGraph(CorrFrame& f) {
  f.dl = ImGui::GetWindowDrawList();
  const ImGuiIO& io = ImGui::GetIO();
  f.mouse = glm::vec2(io.MousePos.x, io.MousePos.y);
  f.ra = buildCorrRows(f.src.blobTree, f.st.toggledA, f.setup.graph, true);
  f.rb = buildCorrRows(f.dst.blobTree, f.st.toggledB, f.setup.graph, false);
  f.rowH = ImGui::GetTextLineHeightWithSpacing() + 2.0f;
  f.origin = ImGui::GetCursorScreenPos();
  f.avail = glm::vec2(std::max(1.0f, ImGui::GetContentRegionAvail().x), std::max(1.0f, ImGui::GetContentRegionAvail().y));
  f.gap = std::clamp(f.avail.x * 0.3f, 80.0f, 360.0f);
  f.colW = std::max(120.0f, (f.avail.x - f.gap) * 0.5f);
  const float headerH = f.rowH;
  const size_t rowCount = std::max(f.ra.rows.size(), f.rb.rows.size());
  f.content = glm::vec2(2.0f * f.colW + f.gap, headerH + float(rowCount) * f.rowH + 4.0f);
}

// The view as spans of content units over the graph's pixels, for the shared zoom / pan helpers.
void viewSpans(const CorrFrame& f, double& x0, double& x1, double& y0, double& y1) {
  x0 = -f.st.pan.x / f.st.zoom, x1 = x0 + f.avail.x / f.st.zoom;
  y0 = -f.st.pan.y / f.st.zoom, y1 = y0 + f.avail.y / f.st.zoom;
}

void setView(CorrFrame& f, double x0, double x1, double y0) {
  f.st.zoom = float(f.avail.x / (x1 - x0));
  f.st.pan = {float(-x0 * f.st.zoom), float(-y0 * f.st.zoom)};
}

// F: frame all (every visible row fits); wheel: zoom around the mouse; middle drag: pan.
void navigateGraph(CorrFrame& f) {
  CorrespondenceEditorState& st = f.st;
  const ImGuiIO& io = ImGui::GetIO();
  const bool viewHovered = ImGui::IsWindowHovered(ImGuiHoveredFlags_AllowWhenBlockedByActiveItem);
  if (st.frameAllNext || (st.focused && !io.WantTextInput && !io.KeyCtrl && !io.KeyAlt && ImGui::IsKeyPressed('F', false))) {
    st.zoom = std::clamp(std::min(f.avail.x / f.content.x, f.avail.y / f.content.y), kMinZoom, kMaxZoom);
    st.pan = {std::max(0.0f, 0.5f * (f.avail.x - f.content.x * st.zoom)), 0.0f};
    st.frameAllNext = false;
  }
  if (viewHovered && io.MouseWheel != 0.0f) {
    double x0, x1, y0, y1;
    viewSpans(f, x0, x1, y0, y1);
    const float target = std::clamp(float(st.zoom / wheelSpanFactor(io.MouseWheel)), kMinZoom, kMaxZoom);
    const double factor = st.zoom / target;
    const glm::vec2 pivot = (f.mouse - glm::vec2(f.origin.x, f.origin.y) - st.pan) / st.zoom;
    scaleSpanAround(x0, x1, pivot.x, factor);
    scaleSpanAround(y0, y1, pivot.y, factor);
    setView(f, x0, x1, y0);
  }
  if (viewHovered && ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f) &&
      (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    double x0, x1, y0, y1;
    viewSpans(f, x0, x1, y0, y1);
    panSpan(x0, x1, io.MouseDelta.x, f.avail.x);
    panSpan(y0, y1, io.MouseDelta.y, f.avail.y);
    setView(f, x0, x1, y0);
  }
  f.z = st.zoom;
}

// The graph: rows, wires, the wire being dragged, picking, menus and the knife.
void drawGraph(Document& doc, const Actor& src, const Actor& dst, CorrespondenceEditorState& st,
               StatusMessage& status) {
  // Commands below may replace the setup: read the graph from this copy.
  CorrFrame f{doc, st, status, src, dst, doc.project().animorphosis};
  // The graph does not scroll: the wheel zooms, a middle drag pans (view_zoom.h).
  ImGui::BeginChild("##corr_graph", ImVec2(0.0f, 0.0f), true,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoScrollbar);
  layOutGraph(f);
  navigateGraph(f);
  drawCorrHeaders(f);
  const ImVec2 clipMin = ImGui::GetWindowPos();
  f.clipTop = clipMin.y, f.clipBottom = clipMin.y + ImGui::GetWindowSize().y;
  // Rows: an arrow (open / close), the node's name and kind, and its link state.
  drawCorrRows(f, 0, 0.0f, f.colW);
  drawCorrRows(f, 1, f.colW + f.gap, 2.0f * f.colW + f.gap);
  ImGui::SetCursorScreenPos(f.origin);
  ImGui::Dummy(ImVec2(f.avail.x, f.avail.y));
  drawCorrLinkWires(f);
  drawCorrSuggestionWires(f);
  // Dragging a new wire from a row; dropping it on a row of the other tree links them.
  drawDraggedCorrWire(f);
  dropCorrWire(f);
  // Clicking near a wire selects it; right-click offers Cut and the s(u) choices.
  f.graphHovered = ImGui::IsWindowHovered();
  clickCorrWires(f);
  drawCorrSuggestionMenu(f);
  drawCorrWireMenu(f);
  cutCorrWiresWithKnife(f);
  ImGui::EndChild();
}

}  // namespace

glm::vec2 CorrFrame::toScreen(float cx, float cy) const {
  return glm::vec2(origin.x + st.pan.x + cx * z, origin.y + st.pan.y + cy * z);
}

glm::vec2 CorrFrame::socketA(int id) const {
  const CorrRow& r = ra.rows[size_t(ra.rowOf.at(id))];
  return glm::vec2(r.max.x - 4.0f * z, r.min.y + rowH * 0.5f * z);
}

glm::vec2 CorrFrame::socketB(int id) const {
  const CorrRow& r = rb.rows[size_t(rb.rowOf.at(id))];
  return glm::vec2(r.min.x + 4.0f * z, r.min.y + rowH * 0.5f * z);
}

void drawCorrespondenceEditor(const LayoutRect& area, Document& doc, CorrespondenceEditorState& st,
                              MorphPanelState& morph, StatusMessage& status) {
  st.hovered = {};
  if (!beginDockedToolWindow("Correspondence Editor", ImVec2(area.min.x, area.min.y), ImVec2(area.size.x, area.size.y),
                             "corr/window", {st.visible, st.placeNext, st.focused}))
    return;
  const Project& project = doc.project();
  const AnimorphosisSetup& m = project.animorphosis;
  const Actor* src = project.findActor(m.sourceActorId);
  const Actor* dst = project.findActor(m.targetActorId);
  const bool chains = project.morph.enabled() && project.morph.method == MorphMethod::SkeletonCorrespondence;
  const bool graph = m.enabled() && src && dst && src->kind == ActorKind::BlobTree && dst->kind == ActorKind::BlobTree;
  if (showsMorphChainTab(chains, graph)) {
    drawMorphChainTab(doc, morph);
    ImGui::End();
    return;
  }
  if (!graph) {
    ImGui::TextDisabled(m.enabled() ? "The animorphosis' source or target is not a BlobTree actor of the project."
                                    : "The project has no animorphosis: Create > Animorphosis... makes one.");
    ImGui::End();
    return;
  }
  keepCorrSelection(st, m);
  drawCorrToolbar(doc, src->blobTree, dst->blobTree, st, status);
  drawGraph(doc, *src, *dst, st, status);
  deleteSelectedCorrLink(doc, st, status);
  ImGui::End();
}

}  // namespace animorph
