// The correspondence editor's drawing: the toolbar, the trees' rows and the wires
// (correspondence_editor_intern.h).
#include <algorithm>
#include <string>

#include <imgui.h>

#include "core/animorphosis/tree_index.h"
#include "core/doc/animorphosis_commands.h"
#include "ui/animorphosis/correspondence_editor_intern.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

glm::vec2 bezierPoint(glm::vec2 p0, glm::vec2 p1, glm::vec2 p2, glm::vec2 p3, float t) {
  const float u = 1.0f - t;
  return u * u * u * p0 + 3.0f * u * u * t * p1 + 3.0f * u * t * t * p2 + t * t * t * p3;
}

// Automatic links: red (0) through yellow to green (1) with the confidence.
ImU32 confidenceColor(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  const glm::vec3 red(0.90f, 0.30f, 0.25f), yellow(0.92f, 0.80f, 0.25f), green(0.35f, 0.82f, 0.40f);
  glm::vec3 rgb = c < 0.5f ? glm::mix(red, yellow, c * 2.0f) : glm::mix(yellow, green, (c - 0.5f) * 2.0f);
  return ImGui::GetColorU32(ImVec4(rgb.r, rgb.g, rgb.b, 0.9f));
}
constexpr ImU32 kArtistColor = IM_COL32(90, 170, 255, 255);
constexpr ImU32 kSelectedColor = IM_COL32(255, 255, 255, 255);

std::string nodeTitle(const BlobNode& n) {
  const char* kind = nodeTypeInfo(n.type).name;
  return n.name.empty() ? std::string(kind) : n.name;
}

// Auto-map, Bake to key-frame actor, Ghosts, Cut and Accept all. Returns the number of
// suggestions before Accept all (the count the toolbar shows this frame).
size_t drawToolbarButtons(Document& doc, CorrespondenceEditorState& st, StatusMessage& status) {
  const AnimorphosisSetup& m = doc.project().animorphosis;
  if (ImGui::Button("Auto-map")) st.autoMapRequested = true;
  noteWidget("corr/automap");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Propose the automatic links again (kind, place and extent over the clip, across wrappers, "
                      "regrouped parts and split segments); links it is unsure of become suggestions (dashed); "
                      "artist links are kept. Runs in the background: Esc or Cancel leaves the links as they are.");
  ImGui::SameLine();
  if (ImGui::Button("Bake to key-frame actor")) st.bakeRequested = true;
  noteWidget("corr/bake_keys");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Bake the animorphosis into a new key-framed BlobTree actor (Animorphosis menu; undoable).");
  ImGui::SameLine();
  bool ghosts = m.showGhosts;
  if (ImGui::Checkbox("Ghosts", &ghosts)) {
    AnimorphosisSetup after = m;
    after.showGhosts = ghosts;
    const std::string label = ghosts ? "Show ghosts of source and target" : "Hide ghosts of source and target";
    doc.execute(setAnimorphosisCommand(doc.project(), std::move(after), label));
    status = {label, false};
  }
  noteWidget("corr/ghosts");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Within the interval the viewport also shows the source and the target, translucent.");
  ImGui::SameLine();
  const bool any = st.selected && m.graph.find(st.selected->nodeA, st.selected->nodeB) >= 0;
  ImGui::BeginDisabled(!any);
  if (ImGui::Button("Cut") && any) {
    runCorrCommand(doc, removeCorrespondenceLinkCommand(doc.project(), st.selected->nodeA, st.selected->nodeB), status);
    st.selected.reset();
  }
  noteWidget("corr/cut");
  ImGui::EndDisabled();
  ImGui::SameLine();
  const size_t suggestions = m.graph.suggestions.size();
  ImGui::BeginDisabled(suggestions == 0);
  const std::string acceptAll = "Accept all (" + std::to_string(suggestions) + ")";
  if (ImGui::Button(acceptAll.c_str()) && suggestions > 0) {
    int accepted = 0;
    auto cmd = acceptAllSuggestionsCommand(doc.project(), &accepted);
    const int left = int(suggestions) - accepted;
    runCorrCommand(doc, std::move(cmd), status,
                   left > 0 ? "; " + std::to_string(left) + " would break a rule of the graph and stay suggestions"
                            : "");
    st.selectedSuggestion.reset();
  }
  noteWidget("corr/accept_all");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Apply every suggestion (dashed wire) that keeps the graph valid, most confident first.");
  ImGui::EndDisabled();
  return suggestions;
}

// The selected suggestion (with Accept) or link (with its s(u) choice); else a hint.
void drawSelectionLine(Document& doc, const BlobTree& a, const BlobTree& b, CorrespondenceEditorState& st,
                       StatusMessage& status, int sel) {
  const AnimorphosisSetup& m = doc.project().animorphosis;
  const int sug =
      st.selectedSuggestion ? m.graph.findSuggestion(st.selectedSuggestion->nodeA, st.selectedSuggestion->nodeB) : -1;
  if (sel < 0 && sug >= 0) {
    const CorrespondenceLink& l = m.graph.suggestions[size_t(sug)];
    const BlobNode* na = a.find(l.nodeA);
    const BlobNode* nb = b.find(l.nodeB);
    // The button first: the docked editor may be too narrow for the whole line.
    if (ImGui::SmallButton("Accept")) {
      runCorrCommand(doc, acceptSuggestionCommand(doc.project(), l.nodeA, l.nodeB), status);
      st.selectedSuggestion.reset();
    }
    noteWidget("corr/accept");
    ImGui::SameLine();
    ImGui::Text("%s -> %s  |  suggestion, confidence %.2f (not applied)", na ? nameOfNode(*na).c_str() : "?",
                nb ? nameOfNode(*nb).c_str() : "?", l.confidence);
    return;
  }
  if (sel < 0) {
    ImGui::TextDisabled("Drag from a node onto a node of the other tree to link; click a wire to select it.");
    return;
  }
  const CorrespondenceLink& l = m.graph.links[size_t(sel)];
  const BlobNode* na = a.find(l.nodeA);
  const BlobNode* nb = b.find(l.nodeB);
  // The button first: the docked editor may be too narrow for the whole line.
  if (!l.sOverride) {
    if (ImGui::SmallButton("Own s(u)"))
      runCorrCommand(doc, setLinkSOverrideCommand(doc.project(), l.nodeA, l.nodeB, m.globalS), status);
    noteWidget("corr/own_s");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Give this link its own s(u) (starting as the global one), edited in the curve editor.");
  } else {
    if (ImGui::SmallButton("Inherit s(u)"))
      runCorrCommand(doc, setLinkSOverrideCommand(doc.project(), l.nodeA, l.nodeB, std::nullopt), status);
    noteWidget("corr/inherit_s");
  }
  ImGui::SameLine();
  ImGui::Text("%s -> %s  |  %s, confidence %.2f  |  s(u): %s", na ? nameOfNode(*na).c_str() : "?",
              nb ? nameOfNode(*nb).c_str() : "?", l.artist ? "artist" : "automatic", l.confidence,
              l.sOverride ? "its own" : "inherited");
}

void drawText(const CorrFrame& f, glm::vec2 at, ImU32 col, const std::string& s) {
  f.dl->AddText(ImGui::GetFont(), ImGui::GetFontSize() * f.z, ImVec2(at.x, at.y), col, s.c_str());
}

float textWidth(const CorrFrame& f, const std::string& s) { return ImGui::CalcTextSize(s.c_str()).x * f.z; }

// A row's open / close arrow at (cx, cy).
void drawRowArrow(const CorrFrame& f, bool open, float cx, float cy) {
  const float z = f.z;
  const ImU32 arrow = IM_COL32(180, 180, 190, 255);
  if (open)
    f.dl->AddTriangleFilled(ImVec2(cx - 4 * z, cy - 2 * z), ImVec2(cx + 4 * z, cy - 2 * z), ImVec2(cx, cy + 3 * z),
                            arrow);
  else
    f.dl->AddTriangleFilled(ImVec2(cx - 2 * z, cy - 4 * z), ImVec2(cx + 3 * z, cy), ImVec2(cx - 2 * z, cy + 4 * z),
                            arrow);
}

// The node's name, its kind and its link state: "x k" for a node split k ways; the top of an
// unlinked sub-tree grows or shrinks.
void drawRowLabel(const CorrFrame& f, const CorrTreeRows& t, const CorrRow& r, int side, float indentX) {
  const BlobNode& n = *r.node;
  const float z = f.z;
  const int direct = int((side == 0 ? f.setup.graph.linksOfA(n.id) : f.setup.graph.linksOfB(n.id)).size());
  const bool unlinked = t.linksIn.at(n.id) == 0;
  const int parent = t.parentOf.at(n.id);
  const bool topUnlinked = unlinked && parent >= 0 && t.linksIn.at(parent) > 0;
  const ImU32 textCol = unlinked && !topUnlinked ? IM_COL32(140, 140, 150, 255) : IM_COL32(225, 225, 230, 255);
  std::string label = nodeTitle(n);
  const float tx = indentX + kCorrArrowW * z, ty = r.min.y + 2.0f * z;
  drawText(f, {tx, ty}, textCol, label);
  float after = tx + textWidth(f, label) + 6.0f * z;
  if (!n.name.empty()) {  // an unnamed node's title is its kind already
    const std::string kind = nodeTypeInfo(n.type).name;
    drawText(f, {after, ty}, IM_COL32(130, 130, 145, 255), kind);
    after += textWidth(f, kind) + 8.0f * z;
  }
  std::string badge;
  ImU32 badgeCol = IM_COL32(240, 200, 90, 255);
  if (direct >= 2) badge = "x " + std::to_string(direct);
  else if (topUnlinked) {
    badge = side == 0 ? "shrinks" : "grows";
    badgeCol = side == 0 ? IM_COL32(230, 130, 110, 255) : IM_COL32(120, 220, 140, 255);
  }
  if (!badge.empty()) drawText(f, {after, ty}, badgeCol, badge);
}

void drawRow(const CorrFrame& f, const CorrTreeRows& t, const CorrRow& r, int side, float indentX, CorrRowHit hit) {
  const CorrespondenceEditorState& st = f.st;
  const BlobNode& n = *r.node;
  const float z = f.z;
  const bool selectedEnd = st.selected && (side == 0 ? st.selected->nodeA : st.selected->nodeB) == n.id;
  if (hit.hovered || hit.dropTarget || selectedEnd)
    f.dl->AddRectFilled(ImVec2(r.min.x, r.min.y), ImVec2(r.max.x, r.max.y),
                        hit.dropTarget ? IM_COL32(90, 170, 255, 90) : IM_COL32(255, 255, 255, selectedEnd ? 40 : 22),
                        3.0f);
  if (!n.children.empty()) drawRowArrow(f, r.open, indentX + 5.0f * z, r.min.y + f.rowH * 0.5f * z);
  drawRowLabel(f, t, r, side, indentX);
  // The socket wires attach to.
  const float sx = side == 0 ? r.max.x - 4.0f * z : r.min.x + 4.0f * z;
  f.dl->AddCircleFilled(ImVec2(sx, r.min.y + f.rowH * 0.5f * z), std::max(1.5f, 3.0f * z),
                        t.linksIn.at(n.id) > 0 ? IM_COL32(200, 200, 210, 255) : IM_COL32(90, 90, 100, 255));
}

// A wire whose both ends are above, or both below, the visible rows shows nothing.
bool offScreen(const CorrFrame& f, const CorrWire& w) {
  return (w.p0.y < f.clipTop && w.p3.y < f.clipTop) || (w.p0.y > f.clipBottom && w.p3.y > f.clipBottom);
}

void drawBezier(const CorrFrame& f, const CorrWire& w, ImU32 col, float thick) {
  f.dl->AddBezierCubic(ImVec2(w.p0.x, w.p0.y), ImVec2(w.c1().x, w.c1().y), ImVec2(w.c2().x, w.c2().y),
                       ImVec2(w.p3.x, w.p3.y), col, thick, kCorrWireSamples);
}

}  // namespace

glm::vec2 CorrWire::c1() const { return p0 + glm::vec2(std::max(30.0f, 0.4f * (p3.x - p0.x)), 0.0f); }
glm::vec2 CorrWire::c2() const { return p3 - glm::vec2(std::max(30.0f, 0.4f * (p3.x - p0.x)), 0.0f); }
glm::vec2 CorrWire::at(float t) const { return bezierPoint(p0, c1(), c2(), p3, t); }

void drawCorrToolbar(Document& doc, const BlobTree& a, const BlobTree& b, CorrespondenceEditorState& st,
                     StatusMessage& status) {
  const size_t suggestions = drawToolbarButtons(doc, st, status);
  const AnimorphosisSetup& m = doc.project().animorphosis;
  // After an auto-map or a cut the graph is another one: look the selection up again.
  const int sel = st.selected ? m.graph.find(st.selected->nodeA, st.selected->nodeB) : -1;
  ImGui::SameLine();
  int artist = 0;
  for (const CorrespondenceLink& l : m.graph.links) artist += l.artist ? 1 : 0;
  ImGui::TextDisabled("%zu link%s (%d artist), %zu suggestion%s  |  %s -> %s", m.graph.links.size(),
                      m.graph.links.size() == 1 ? "" : "s", artist, suggestions, suggestions == 1 ? "" : "s",
                      m.sourceActorId.c_str(), m.targetActorId.c_str());
  drawSelectionLine(doc, a, b, st, status, sel);
}

void drawCorrHeaders(const CorrFrame& f) {
  drawText(f, f.toScreen(0.0f, 0.0f), IM_COL32(200, 200, 210, 255), "Source: " + f.src.name);
  drawText(f, f.toScreen(f.colW + f.gap, 0.0f), IM_COL32(200, 200, 210, 255), "Target: " + f.dst.name);
}

void drawCorrRows(CorrFrame& f, int side, float x0, float x1) {
  CorrTreeRows& t = side == 0 ? f.ra : f.rb;
  const float headerH = f.rowH;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    CorrRow& r = t.rows[i];
    r.min = f.toScreen(x0, headerH + float(i) * f.rowH);
    r.max = f.toScreen(x1, headerH + float(i + 1) * f.rowH - 1.0f);
    if (r.max.y < f.clipTop || r.min.y > f.clipBottom) continue;
    // The target's sockets are on the left of its rows: its text starts after them.
    const float indentX = r.min.x + ((side == 0 ? 4.0f : 12.0f) + r.depth * kCorrIndent) * f.z;
    const CorrRowHit hit = pressCorrRow(f, r, side, indentX);
    drawRow(f, t, r, side, indentX, hit);
  }
}

void drawCorrLinkWires(CorrFrame& f) {
  const CorrespondenceEditorState& st = f.st;
  const CorrespondenceGraph& graph = f.setup.graph;
  f.wires.reserve(graph.links.size());
  for (size_t i = 0; i < graph.links.size(); ++i) {
    const CorrespondenceLink& l = graph.links[i];
    // Links to nodes inside closed sub-trees end at the closed row.
    if (!f.ra.rowOf.count(l.nodeA) || !f.rb.rowOf.count(l.nodeB)) continue;
    CorrWire w{int(i), f.socketA(l.nodeA), f.socketB(l.nodeB)};
    if (offScreen(f, w)) continue;
    f.wires.push_back(w);
    const bool isSel = st.selected && st.selected->nodeA == l.nodeA && st.selected->nodeB == l.nodeB;
    const ImU32 col = isSel ? kSelectedColor : l.artist ? kArtistColor : confidenceColor(l.confidence);
    drawBezier(f, w, col, isSel ? 3.5f : l.artist ? 2.8f : 1.5f);
    const glm::vec2 mid = w.at(0.5f);
    if (l.sOverride) f.dl->AddCircleFilled(ImVec2(mid.x, mid.y), 4.0f, col);  // its own s(u): a dot at its middle
    noteWidgetRect("corr/link/" + std::to_string(l.nodeA) + "-" + std::to_string(l.nodeB), mid - glm::vec2(3.0f),
                   mid + glm::vec2(3.0f));
  }
}

void drawCorrSuggestionWires(CorrFrame& f) {
  const CorrespondenceEditorState& st = f.st;
  const CorrespondenceGraph& graph = f.setup.graph;
  for (size_t i = 0; i < graph.suggestions.size(); ++i) {
    const CorrespondenceLink& l = graph.suggestions[i];
    if (!f.ra.rowOf.count(l.nodeA) || !f.rb.rowOf.count(l.nodeB)) continue;
    CorrWire w{int(i), f.socketA(l.nodeA), f.socketB(l.nodeB)};
    if (offScreen(f, w)) continue;
    f.suggestionWires.push_back(w);
    const bool isSel = st.selectedSuggestion && st.selectedSuggestion->nodeA == l.nodeA &&
                       st.selectedSuggestion->nodeB == l.nodeB;
    const ImU32 col = isSel ? kSelectedColor : ImU32(kSuggestionWireColor);
    for (int k = 0; k < kCorrWireSamples; k += 2) {  // every other piece of the curve: a dashed wire
      glm::vec2 p = w.at(float(k) / kCorrWireSamples), q = w.at(float(k + 1) / kCorrWireSamples);
      f.dl->AddLine(ImVec2(p.x, p.y), ImVec2(q.x, q.y), col, isSel ? 2.5f : 1.5f);
    }
    const glm::vec2 mid = w.at(0.5f);
    f.dl->AddCircle(ImVec2(mid.x, mid.y), 4.0f, col, 12, 1.5f);
    noteWidgetRect("corr/suggestion/" + std::to_string(l.nodeA) + "-" + std::to_string(l.nodeB),
                   mid - glm::vec2(3.0f), mid + glm::vec2(3.0f));
  }
}

void drawDraggedCorrWire(const CorrFrame& f) {
  const CorrespondenceEditorState& st = f.st;
  if (st.dragSide < 0) return;
  const bool fromA = st.dragSide == 0;
  const CorrTreeRows& from = fromA ? f.ra : f.rb;
  if (!from.rowOf.count(st.dragNode)) return;
  glm::vec2 p0 = fromA ? f.socketA(st.dragNode) : f.socketB(st.dragNode);
  glm::vec2 p3 = f.mouse;
  if (!fromA) std::swap(p0, p3);
  drawBezier(f, CorrWire{-1, p0, p3}, kArtistColor, 2.0f);
}

void drawCorrKnifeTrail(const CorrFrame& f) {
  const std::vector<glm::vec2>& trail = f.st.cutTrail;
  for (size_t k = 1; k < trail.size(); ++k)
    f.dl->AddLine(ImVec2(trail[k - 1].x, trail[k - 1].y), ImVec2(trail[k].x, trail[k].y), IM_COL32(255, 90, 80, 255),
                  1.5f);
}

}  // namespace animorph
