// The correspondence editor: the source and target trees side by side, the
// correspondence graph as wires between their rows (animorphosis_panel.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>
#include <vector>

#include <imgui.h>

#include "core/animorphosis/tree_index.h"
#include "core/doc/animorphosis_commands.h"
#include "core/project/animorphosis_project.h"
#include "ui/animorphosis/animorphosis_panel.h"
#include "ui/widgets/tool_window.h"
#include "ui/widgets/view_zoom.h"
#include "ui/widgets/widget_rects.h"
#include "ui/common/command_result.h"

namespace animorph {

namespace {

constexpr float kIndent = 14.0f;    // per depth level
constexpr float kArrowW = 14.0f;    // the open / close arrow at the start of a row
constexpr float kPickPx = 6.0f;     // a click this close to a wire selects it
constexpr int kWireSamples = 24;    // segments of a wire's Bezier for picking and cutting
constexpr int kDefaultOpenDepth = 3;
constexpr float kMinZoom = 0.15f, kMaxZoom = 4.0f;

struct Row {
  const BlobNode* node = nullptr;
  int depth = 0;
  bool open = false;
  glm::vec2 min{0.0f}, max{0.0f};  // screen rect, set when laid out
};

// One tree's visible rows, and for every node the row showing it (its nearest
// visible ancestor-or-self).
struct TreeRows {
  std::vector<Row> rows;
  std::unordered_map<int, int> rowOf;
  std::unordered_map<int, int> linksIn;  // links inside each node's sub-tree (itself included)
  std::unordered_map<int, int> parentOf;
};

void collectRows(const BlobNode& n, int depth, int parent, int shownRow, const std::set<int>& toggled, TreeRows& t) {
  t.parentOf[n.id] = parent;
  if (shownRow < 0) {
    Row r;
    r.node = &n;
    r.depth = depth;
    r.open = !n.children.empty() && ((depth < kDefaultOpenDepth) != (toggled.count(n.id) != 0));
    t.rows.push_back(r);
    t.rowOf[n.id] = int(t.rows.size()) - 1;
    const int childRow = r.open ? -1 : int(t.rows.size()) - 1;
    for (const BlobNode& c : n.children) collectRows(c, depth + 1, n.id, childRow, toggled, t);
  } else {
    t.rowOf[n.id] = shownRow;
    for (const BlobNode& c : n.children) collectRows(c, depth + 1, n.id, shownRow, toggled, t);
  }
}

int countLinksIn(const BlobNode& n, const std::unordered_map<int, int>& direct, TreeRows& t) {
  auto it = direct.find(n.id);
  int count = it == direct.end() ? 0 : it->second;
  for (const BlobNode& c : n.children) count += countLinksIn(c, direct, t);
  t.linksIn[n.id] = count;
  return count;
}

TreeRows buildRows(const BlobTree& tree, const std::set<int>& toggled, const CorrespondenceGraph& g, bool sourceSide) {
  TreeRows t;
  collectRows(tree.root, 0, -1, -1, toggled, t);
  std::unordered_map<int, int> direct;
  for (const CorrespondenceLink& l : g.links) ++direct[sourceSide ? l.nodeA : l.nodeB];
  countLinksIn(tree.root, direct, t);
  return t;
}

glm::vec2 bezierPoint(glm::vec2 p0, glm::vec2 p1, glm::vec2 p2, glm::vec2 p3, float t) {
  const float u = 1.0f - t;
  return u * u * u * p0 + 3.0f * u * u * t * p1 + 3.0f * u * t * t * p2 + t * t * t * p3;
}

struct Wire {
  int link = -1;
  glm::vec2 p0{0.0f}, p3{0.0f};
  glm::vec2 c1() const { return p0 + glm::vec2(std::max(30.0f, 0.4f * (p3.x - p0.x)), 0.0f); }
  glm::vec2 c2() const { return p3 - glm::vec2(std::max(30.0f, 0.4f * (p3.x - p0.x)), 0.0f); }
  glm::vec2 at(float t) const { return bezierPoint(p0, c1(), c2(), p3, t); }
};

float segmentDistance(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  glm::vec2 ab = b - a;
  float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

float wireDistance(const Wire& w, glm::vec2 p) {
  float best = 1e30f;
  glm::vec2 prev = w.p0;
  for (int i = 1; i <= kWireSamples; ++i) {
    glm::vec2 q = w.at(float(i) / kWireSamples);
    best = std::min(best, segmentDistance(p, prev, q));
    prev = q;
  }
  return best;
}

// True when segments ab and cd cross.
bool segmentsCross(glm::vec2 a, glm::vec2 b, glm::vec2 c, glm::vec2 d) {
  auto cross = [](glm::vec2 u, glm::vec2 v) { return u.x * v.y - u.y * v.x; };
  const float d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0.0f) != (d2 > 0.0f)) && ((d3 > 0.0f) != (d4 > 0.0f));
}

bool wireCrossesTrail(const Wire& w, const std::vector<glm::vec2>& trail) {
  glm::vec2 prev = w.p0;
  for (int i = 1; i <= kWireSamples; ++i) {
    glm::vec2 q = w.at(float(i) / kWireSamples);
    for (size_t k = 1; k < trail.size(); ++k)
      if (segmentsCross(prev, q, trail[k - 1], trail[k])) return true;
    prev = q;
  }
  return false;
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

void runCommand(Document& doc, Result<std::unique_ptr<Command>> cmd, StatusMessage& status, std::string note = {}) {
  if (executeOrReport(doc, std::move(cmd), status, /*announce=*/true)) status.text += note;
}

void autoMap(Document& doc, StatusMessage& status) {
  const Project& p = doc.project();
  const AnimorphosisTiming t = animorphosisTiming(p);
  AutoCorrespondSettings settings;
  settings.timeSecA = t.source.localTime(t.startSec);
  settings.timeSecB = t.target.localTime(t.startSec);
  AutoCorrespondReport report;
  auto cmd = autoMapCommand(p, settings, &report);
  char buf[160];
  std::snprintf(buf, sizeof buf, ": %d proposed (mean confidence %.2f), %d suggested, %d artist link%s kept",
                report.proposed, report.meanConfidence, report.suggested, report.artistKept,
                report.artistKept == 1 ? "" : "s");
  runCommand(doc, std::move(cmd), status, buf);
}

// The toolbar: Auto-map, Cut, the selected link and its s(u).
void drawToolbar(Document& doc, const BlobTree& a, const BlobTree& b, CorrespondenceEditorState& st,
                 StatusMessage& status) {
  const AnimorphosisSetup& m = doc.project().animorphosis;
  if (ImGui::Button("Auto-map")) autoMap(doc, status);
  noteWidget("corr/automap");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Propose the automatic links again (kind, place and extent over the clip, across wrappers, "
                      "regrouped parts and split segments); links it is unsure of become suggestions (dashed); "
                      "artist links are kept.");
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
    runCommand(doc, removeCorrespondenceLinkCommand(doc.project(), st.selected->nodeA, st.selected->nodeB), status);
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
    runCommand(doc, std::move(cmd), status,
               left > 0 ? "; " + std::to_string(left) + " would break a rule of the graph and stay suggestions" : "");
    st.selectedSuggestion.reset();
  }
  noteWidget("corr/accept_all");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Apply every suggestion (dashed wire) that keeps the graph valid, most confident first.");
  ImGui::EndDisabled();
  // After an auto-map or a cut the graph is another one: look the selection up again.
  const int sel = st.selected ? m.graph.find(st.selected->nodeA, st.selected->nodeB) : -1;
  ImGui::SameLine();
  int artist = 0;
  for (const CorrespondenceLink& l : m.graph.links) artist += l.artist ? 1 : 0;
  ImGui::TextDisabled("%zu link%s (%d artist), %zu suggestion%s  |  %s -> %s", m.graph.links.size(),
                      m.graph.links.size() == 1 ? "" : "s", artist, suggestions, suggestions == 1 ? "" : "s",
                      m.sourceActorId.c_str(), m.targetActorId.c_str());
  const int sug = st.selectedSuggestion ? m.graph.findSuggestion(st.selectedSuggestion->nodeA, st.selectedSuggestion->nodeB) : -1;
  if (sel < 0 && sug >= 0) {
    const CorrespondenceLink& l = m.graph.suggestions[size_t(sug)];
    const BlobNode* na = a.find(l.nodeA);
    const BlobNode* nb = b.find(l.nodeB);
    // The button first: the docked editor may be too narrow for the whole line.
    if (ImGui::SmallButton("Accept")) {
      runCommand(doc, acceptSuggestionCommand(doc.project(), l.nodeA, l.nodeB), status);
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
      runCommand(doc, setLinkSOverrideCommand(doc.project(), l.nodeA, l.nodeB, m.globalS), status);
    noteWidget("corr/own_s");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Give this link its own s(u) (starting as the global one), edited in the curve editor.");
  } else {
    if (ImGui::SmallButton("Inherit s(u)"))
      runCommand(doc, setLinkSOverrideCommand(doc.project(), l.nodeA, l.nodeB, std::nullopt), status);
    noteWidget("corr/inherit_s");
  }
  ImGui::SameLine();
  ImGui::Text("%s -> %s  |  %s, confidence %.2f  |  s(u): %s", na ? nameOfNode(*na).c_str() : "?",
              nb ? nameOfNode(*nb).c_str() : "?", l.artist ? "artist" : "automatic", l.confidence,
              l.sOverride ? "its own" : "inherited");
}

}  // namespace

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
  bool chainTab = chains && !graph;
  if (chains && graph) {  // both: a tab each
    if (ImGui::BeginTabBar("##corr_tabs")) {
      if (ImGui::BeginTabItem("Animorphosis")) ImGui::EndTabItem();
      noteWidget("corr/tab/animorphosis");
      if (ImGui::BeginTabItem("Morph chains")) {
        chainTab = true;
        ImGui::EndTabItem();
      }
      noteWidget("corr/tab/chains");
      ImGui::EndTabBar();
    }
  }
  if (chainTab) {
    ImGui::TextDisabled("Morph %s -> %s: skeleton correspondence by chains", project.morph.sourceActorId.c_str(),
                        project.morph.targetActorId.c_str());
    drawChainMatching(doc, morph, "corr/chains");
    ImGui::End();
    return;
  }
  if (!graph) {
    ImGui::TextDisabled(m.enabled() ? "The animorphosis' source or target is not a BlobTree actor of the project."
                                    : "The project has no animorphosis: Create > Animorphosis... makes one.");
    ImGui::End();
    return;
  }
  const std::string key = m.sourceActorId + "->" + m.targetActorId;
  if (st.treesKey != key) {
    st.treesKey = key;
    st.toggledA.clear();
    st.toggledB.clear();
    st.selected.reset();
    st.selectedSuggestion.reset();
  }
  if (st.selected && m.graph.find(st.selected->nodeA, st.selected->nodeB) < 0) st.selected.reset();
  drawToolbar(doc, src->blobTree, dst->blobTree, st, status);
  // Commands below may replace the setup: read the graph from this copy.
  const AnimorphosisSetup setup = m;
  const BlobTree& treeA = src->blobTree;
  const BlobTree& treeB = dst->blobTree;

  // The graph does not scroll: the wheel zooms, a middle drag pans (view_zoom.h).
  ImGui::BeginChild("##corr_graph", ImVec2(0.0f, 0.0f), true,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoScrollbar);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 mouse(io.MousePos.x, io.MousePos.y);
  TreeRows ra = buildRows(treeA, st.toggledA, setup.graph, true);
  TreeRows rb = buildRows(treeB, st.toggledB, setup.graph, false);
  // The layout in content units (pixels at zoom 1): the source's column, the gap the wires cross, the target's.
  const float rowH = ImGui::GetTextLineHeightWithSpacing() + 2.0f;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const glm::vec2 avail(std::max(1.0f, ImGui::GetContentRegionAvail().x), std::max(1.0f, ImGui::GetContentRegionAvail().y));
  const float gap = std::clamp(avail.x * 0.3f, 80.0f, 360.0f);
  const float colW = std::max(120.0f, (avail.x - gap) * 0.5f);
  const float headerH = rowH;
  const size_t rowCount = std::max(ra.rows.size(), rb.rows.size());
  const glm::vec2 content(2.0f * colW + gap, headerH + float(rowCount) * rowH + 4.0f);

  // F: frame all (every visible row fits); wheel: zoom around the mouse; middle drag: pan.
  const bool viewHovered = ImGui::IsWindowHovered(ImGuiHoveredFlags_AllowWhenBlockedByActiveItem);
  if (st.frameAllNext || (st.focused && !io.WantTextInput && !io.KeyCtrl && !io.KeyAlt && ImGui::IsKeyPressed('F', false))) {
    st.zoom = std::clamp(std::min(avail.x / content.x, avail.y / content.y), kMinZoom, kMaxZoom);
    st.pan = {std::max(0.0f, 0.5f * (avail.x - content.x * st.zoom)), 0.0f};
    st.frameAllNext = false;
  }
  // The view as spans of content units over the graph's pixels, for the shared zoom / pan helpers.
  auto viewSpans = [&](double& x0, double& x1, double& y0, double& y1) {
    x0 = -st.pan.x / st.zoom, x1 = x0 + avail.x / st.zoom;
    y0 = -st.pan.y / st.zoom, y1 = y0 + avail.y / st.zoom;
  };
  auto setView = [&](double x0, double x1, double y0) {
    st.zoom = float(avail.x / (x1 - x0));
    st.pan = {float(-x0 * st.zoom), float(-y0 * st.zoom)};
  };
  if (viewHovered && io.MouseWheel != 0.0f) {
    double x0, x1, y0, y1;
    viewSpans(x0, x1, y0, y1);
    const float target = std::clamp(float(st.zoom / wheelSpanFactor(io.MouseWheel)), kMinZoom, kMaxZoom);
    const double f = st.zoom / target;
    const glm::vec2 pivot = (mouse - glm::vec2(origin.x, origin.y) - st.pan) / st.zoom;
    scaleSpanAround(x0, x1, pivot.x, f);
    scaleSpanAround(y0, y1, pivot.y, f);
    setView(x0, x1, y0);
  }
  if (viewHovered && ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f) &&
      (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    double x0, x1, y0, y1;
    viewSpans(x0, x1, y0, y1);
    panSpan(x0, x1, io.MouseDelta.x, avail.x);
    panSpan(y0, y1, io.MouseDelta.y, avail.y);
    setView(x0, x1, y0);
  }
  const float z = st.zoom;
  auto toScreen = [&](float cx, float cy) { return glm::vec2(origin.x + st.pan.x + cx * z, origin.y + st.pan.y + cy * z); };
  ImFont* font = ImGui::GetFont();
  const float fontPx = ImGui::GetFontSize() * z;
  auto text = [&](glm::vec2 at, ImU32 col, const std::string& s) { dl->AddText(font, fontPx, ImVec2(at.x, at.y), col, s.c_str()); };
  auto textW = [&](const std::string& s) { return ImGui::CalcTextSize(s.c_str()).x * z; };
  const float xA0 = 0.0f, xA1 = colW, xB0 = colW + gap, xB1 = xB0 + colW;
  text(toScreen(xA0, 0.0f), IM_COL32(200, 200, 210, 255), "Source: " + src->name);
  text(toScreen(xB0, 0.0f), IM_COL32(200, 200, 210, 255), "Target: " + dst->name);
  const ImVec2 clipMin = ImGui::GetWindowPos();
  const float clipTop = clipMin.y, clipBottom = clipMin.y + ImGui::GetWindowSize().y;

  // Rows: an arrow (open / close), the node's name and kind, and its link state.
  bool rowHovered = false;
  auto drawRows = [&](TreeRows& t, int side, float x0, float x1) {
    std::set<int>& toggled = side == 0 ? st.toggledA : st.toggledB;
    for (size_t i = 0; i < t.rows.size(); ++i) {
      Row& r = t.rows[i];
      r.min = toScreen(x0, headerH + float(i) * rowH);
      r.max = toScreen(x1, headerH + float(i + 1) * rowH - 1.0f);
      if (r.max.y < clipTop || r.min.y > clipBottom) continue;
      const BlobNode& n = *r.node;
      ImGui::SetCursorScreenPos(ImVec2(r.min.x, r.min.y));
      ImGui::PushID(side * 1000003 + n.id);
      ImGui::InvisibleButton("##row", ImVec2(std::max(1.0f, r.max.x - r.min.x), std::max(1.0f, r.max.y - r.min.y)));
      ImGui::PopID();
      noteWidget(std::string(side == 0 ? "corr/a/" : "corr/b/") + std::to_string(n.id));
      const bool hovered = ImGui::IsItemHovered();
      rowHovered |= hovered;
      const bool dropTarget = st.dragSide >= 0 && st.dragSide != side && mouse.x >= r.min.x && mouse.x < r.max.x &&
                              mouse.y >= r.min.y && mouse.y < r.max.y;
      if (hovered || dropTarget) st.hovered = Selection{side == 0 ? src->id : dst->id, n.id};
      // The target's sockets are on the left of its rows: its text starts after them.
      const float indentX = r.min.x + ((side == 0 ? 4.0f : 12.0f) + r.depth * kIndent) * z;
      if (ImGui::IsItemClicked(0)) {
        if (!n.children.empty() && mouse.x >= indentX && mouse.x < indentX + kArrowW * z) {
          if (!toggled.erase(n.id)) toggled.insert(n.id);
        } else {  // the node becomes the document's selection (inspector, outliner)
          doc.selection = Selection{side == 0 ? src->id : dst->id, n.id};
        }
      }
      if (ImGui::IsItemActive() && ImGui::IsMouseDragging(0, 4.0f) && st.dragSide < 0) {
        st.dragSide = side;
        st.dragNode = n.id;
      }
      const bool selectedEnd =
          st.selected && (side == 0 ? st.selected->nodeA : st.selected->nodeB) == n.id;
      if (hovered || dropTarget || selectedEnd)
        dl->AddRectFilled(ImVec2(r.min.x, r.min.y), ImVec2(r.max.x, r.max.y),
                          dropTarget ? IM_COL32(90, 170, 255, 90) : IM_COL32(255, 255, 255, selectedEnd ? 40 : 22),
                          3.0f);
      if (!n.children.empty()) {
        const float cy = r.min.y + rowH * 0.5f * z, cx = indentX + 5.0f * z;
        const ImU32 arrow = IM_COL32(180, 180, 190, 255);
        if (r.open)
          dl->AddTriangleFilled(ImVec2(cx - 4 * z, cy - 2 * z), ImVec2(cx + 4 * z, cy - 2 * z), ImVec2(cx, cy + 3 * z), arrow);
        else
          dl->AddTriangleFilled(ImVec2(cx - 2 * z, cy - 4 * z), ImVec2(cx + 3 * z, cy), ImVec2(cx - 2 * z, cy + 4 * z), arrow);
      }
      // Link state: "x k" for a node split k ways; the top of an unlinked sub-tree grows or shrinks.
      const int direct = int((side == 0 ? setup.graph.linksOfA(n.id) : setup.graph.linksOfB(n.id)).size());
      const bool unlinked = t.linksIn[n.id] == 0;
      const int parent = t.parentOf[n.id];
      const bool topUnlinked = unlinked && parent >= 0 && t.linksIn[parent] > 0;
      const ImU32 textCol = unlinked && !topUnlinked ? IM_COL32(140, 140, 150, 255) : IM_COL32(225, 225, 230, 255);
      std::string label = nodeTitle(n);
      const float tx = indentX + kArrowW * z, ty = r.min.y + 2.0f * z;
      text({tx, ty}, textCol, label);
      float after = tx + textW(label) + 6.0f * z;
      if (!n.name.empty()) {  // an unnamed node's title is its kind already
        const std::string kind = nodeTypeInfo(n.type).name;
        text({after, ty}, IM_COL32(130, 130, 145, 255), kind);
        after += textW(kind) + 8.0f * z;
      }
      std::string badge;
      ImU32 badgeCol = IM_COL32(240, 200, 90, 255);
      if (direct >= 2) badge = "x " + std::to_string(direct);
      else if (topUnlinked) {
        badge = side == 0 ? "shrinks" : "grows";
        badgeCol = side == 0 ? IM_COL32(230, 130, 110, 255) : IM_COL32(120, 220, 140, 255);
      }
      if (!badge.empty()) text({after, ty}, badgeCol, badge);
      // The socket wires attach to.
      const float sx = side == 0 ? r.max.x - 4.0f * z : r.min.x + 4.0f * z;
      dl->AddCircleFilled(ImVec2(sx, r.min.y + rowH * 0.5f * z), std::max(1.5f, 3.0f * z),
                          t.linksIn[n.id] > 0 ? IM_COL32(200, 200, 210, 255) : IM_COL32(90, 90, 100, 255));
    }
  };
  drawRows(ra, 0, xA0, xA1);
  drawRows(rb, 1, xB0, xB1);
  ImGui::SetCursorScreenPos(origin);
  ImGui::Dummy(ImVec2(avail.x, avail.y));

  auto socketA = [&](int id) {
    const Row& r = ra.rows[size_t(ra.rowOf.at(id))];
    return glm::vec2(r.max.x - 4.0f * z, r.min.y + rowH * 0.5f * z);
  };
  auto socketB = [&](int id) {
    const Row& r = rb.rows[size_t(rb.rowOf.at(id))];
    return glm::vec2(r.min.x + 4.0f * z, r.min.y + rowH * 0.5f * z);
  };

  // Wires. Links to nodes inside closed sub-trees end at the closed row.
  std::vector<Wire> wires;
  wires.reserve(setup.graph.links.size());
  for (size_t i = 0; i < setup.graph.links.size(); ++i) {
    const CorrespondenceLink& l = setup.graph.links[i];
    if (!ra.rowOf.count(l.nodeA) || !rb.rowOf.count(l.nodeB)) continue;
    Wire w{int(i), socketA(l.nodeA), socketB(l.nodeB)};
    // Both ends above or both below the visible rows: nothing of it shows.
    if ((w.p0.y < clipTop && w.p3.y < clipTop) || (w.p0.y > clipBottom && w.p3.y > clipBottom)) continue;
    wires.push_back(w);
    const bool isSel = st.selected && st.selected->nodeA == l.nodeA && st.selected->nodeB == l.nodeB;
    const ImU32 col = isSel ? kSelectedColor : l.artist ? kArtistColor : confidenceColor(l.confidence);
    const float thick = isSel ? 3.5f : l.artist ? 2.8f : 1.5f;
    dl->AddBezierCubic(ImVec2(w.p0.x, w.p0.y), ImVec2(w.c1().x, w.c1().y), ImVec2(w.c2().x, w.c2().y),
                       ImVec2(w.p3.x, w.p3.y), col, thick, kWireSamples);
    if (l.sOverride) {  // a link with its own s(u): a dot at its middle
      glm::vec2 mid = w.at(0.5f);
      dl->AddCircleFilled(ImVec2(mid.x, mid.y), 4.0f, col);
    }
    const glm::vec2 mid = w.at(0.5f);
    noteWidgetRect("corr/link/" + std::to_string(l.nodeA) + "-" + std::to_string(l.nodeB), mid - glm::vec2(3.0f),
                   mid + glm::vec2(3.0f));
  }

  // Suggestions: dashed violet wires, apart from the applied links (kSuggestionWireColor).
  std::vector<Wire> suggestionWires;
  for (size_t i = 0; i < setup.graph.suggestions.size(); ++i) {
    const CorrespondenceLink& l = setup.graph.suggestions[i];
    if (!ra.rowOf.count(l.nodeA) || !rb.rowOf.count(l.nodeB)) continue;
    Wire w{int(i), socketA(l.nodeA), socketB(l.nodeB)};
    if ((w.p0.y < clipTop && w.p3.y < clipTop) || (w.p0.y > clipBottom && w.p3.y > clipBottom)) continue;
    suggestionWires.push_back(w);
    const bool isSel = st.selectedSuggestion && st.selectedSuggestion->nodeA == l.nodeA &&
                       st.selectedSuggestion->nodeB == l.nodeB;
    const ImU32 col = isSel ? kSelectedColor : ImU32(kSuggestionWireColor);
    for (int k = 0; k < kWireSamples; k += 2) {  // every other piece of the curve: a dashed wire
      glm::vec2 p = w.at(float(k) / kWireSamples), q = w.at(float(k + 1) / kWireSamples);
      dl->AddLine(ImVec2(p.x, p.y), ImVec2(q.x, q.y), col, isSel ? 2.5f : 1.5f);
    }
    const glm::vec2 mid = w.at(0.5f);
    dl->AddCircle(ImVec2(mid.x, mid.y), 4.0f, col, 12, 1.5f);
    noteWidgetRect("corr/suggestion/" + std::to_string(l.nodeA) + "-" + std::to_string(l.nodeB), mid - glm::vec2(3.0f),
                   mid + glm::vec2(3.0f));
  }

  // Dragging a new wire from a row; dropping it on a row of the other tree links them.
  if (st.dragSide >= 0) {
    const bool fromA = st.dragSide == 0;
    const TreeRows& from = fromA ? ra : rb;
    if (from.rowOf.count(st.dragNode)) {
      glm::vec2 p0 = fromA ? socketA(st.dragNode) : socketB(st.dragNode);
      glm::vec2 p3 = mouse;
      if (!fromA) std::swap(p0, p3);
      Wire w{-1, p0, p3};
      dl->AddBezierCubic(ImVec2(w.p0.x, w.p0.y), ImVec2(w.c1().x, w.c1().y), ImVec2(w.c2().x, w.c2().y),
                         ImVec2(w.p3.x, w.p3.y), kArtistColor, 2.0f, kWireSamples);
    }
    if (!ImGui::IsMouseDown(0)) {
      const TreeRows& to = fromA ? rb : ra;
      int hit = -1;
      for (const Row& r : to.rows)
        if (mouse.x >= r.min.x && mouse.x < r.max.x && mouse.y >= r.min.y && mouse.y < r.max.y) hit = r.node->id;
      if (hit >= 0) {
        const int nodeA = fromA ? st.dragNode : hit, nodeB = fromA ? hit : st.dragNode;
        auto cmd = addCorrespondenceLinkCommand(doc.project(), nodeA, nodeB);
        if (cmd) st.selected = CorrespondenceLinkRef{nodeA, nodeB};
        runCommand(doc, std::move(cmd), status);
      }
      st.dragSide = -1;
      st.dragNode = -1;
    }
  }

  // Clicking near a wire selects it; right-click offers Cut and the s(u) choices.
  const bool graphHovered = ImGui::IsWindowHovered();
  auto nearestWire = [&]() -> int {
    int best = -1;
    float bestD = kPickPx;
    for (const Wire& w : wires) {
      float d = wireDistance(w, mouse);
      if (d <= bestD) bestD = d, best = w.link;
    }
    return best;
  };
  auto nearestSuggestion = [&]() -> int {
    int best = -1;
    float bestD = kPickPx;
    for (const Wire& w : suggestionWires) {
      float d = wireDistance(w, mouse);
      if (d <= bestD) bestD = d, best = w.link;
    }
    return best;
  };
  if (graphHovered && !rowHovered && st.dragSide < 0 && !io.KeyCtrl &&
      (ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1))) {
    const int hit = nearestWire();
    const int hitSuggestion = hit >= 0 ? -1 : nearestSuggestion();
    if (hit >= 0) {
      const CorrespondenceLink& l = setup.graph.links[size_t(hit)];
      st.selected = CorrespondenceLinkRef{l.nodeA, l.nodeB};
      st.selectedSuggestion.reset();
      if (ImGui::IsMouseClicked(1)) ImGui::OpenPopup("##wire_menu");
    } else if (hitSuggestion >= 0) {
      const CorrespondenceLink& l = setup.graph.suggestions[size_t(hitSuggestion)];
      st.selectedSuggestion = CorrespondenceLinkRef{l.nodeA, l.nodeB};
      st.selected.reset();
      if (ImGui::IsMouseDoubleClicked(0)) {
        runCommand(doc, acceptSuggestionCommand(doc.project(), l.nodeA, l.nodeB), status);
        st.selectedSuggestion.reset();
      } else if (ImGui::IsMouseClicked(1)) {
        ImGui::OpenPopup("##suggestion_menu");
      }
    } else if (ImGui::IsMouseClicked(0)) {
      st.selected.reset();
      st.selectedSuggestion.reset();
    }
  }
  if (ImGui::BeginPopup("##suggestion_menu")) {
    if (st.selectedSuggestion && ImGui::MenuItem("Accept")) {
      runCommand(doc, acceptSuggestionCommand(doc.project(), st.selectedSuggestion->nodeA, st.selectedSuggestion->nodeB),
                 status);
      st.selectedSuggestion.reset();
    }
    noteWidget("corr/menu/accept");
    ImGui::EndPopup();
  }
  if (ImGui::BeginPopup("##wire_menu")) {
    if (st.selected) {
      const int i = setup.graph.find(st.selected->nodeA, st.selected->nodeB);
      if (ImGui::MenuItem("Cut")) {
        runCommand(doc, removeCorrespondenceLinkCommand(doc.project(), st.selected->nodeA, st.selected->nodeB), status);
        st.selected.reset();
      }
      noteWidget("corr/menu/cut");
      if (i >= 0 && !setup.graph.links[size_t(i)].sOverride && ImGui::MenuItem("Own s(u)"))
        runCommand(doc, setLinkSOverrideCommand(doc.project(), st.selected->nodeA, st.selected->nodeB, setup.globalS),
                   status);
      if (i >= 0 && setup.graph.links[size_t(i)].sOverride && ImGui::MenuItem("Inherit s(u)"))
        runCommand(doc, setLinkSOverrideCommand(doc.project(), st.selected->nodeA, st.selected->nodeB, std::nullopt),
                   status);
    }
    ImGui::EndPopup();
  }

  // Ctrl+right-drag: a knife; the wires its trail crosses are cut, as one undo step.
  if (graphHovered && io.KeyCtrl && ImGui::IsMouseClicked(1)) st.cutTrail = {mouse};
  if (!st.cutTrail.empty()) {
    if (ImGui::IsMouseDown(1)) {
      if (glm::length(mouse - st.cutTrail.back()) > 3.0f) st.cutTrail.push_back(mouse);
      for (size_t k = 1; k < st.cutTrail.size(); ++k)
        dl->AddLine(ImVec2(st.cutTrail[k - 1].x, st.cutTrail[k - 1].y), ImVec2(st.cutTrail[k].x, st.cutTrail[k].y),
                    IM_COL32(255, 90, 80, 255), 1.5f);
    } else {
      std::vector<CorrespondenceLinkRef> cut;
      for (const Wire& w : wires)
        if (wireCrossesTrail(w, st.cutTrail))
          cut.push_back({setup.graph.links[size_t(w.link)].nodeA, setup.graph.links[size_t(w.link)].nodeB});
      st.cutTrail.clear();
      if (!cut.empty()) {
        AnimorphosisSetup after = doc.project().animorphosis;
        for (const CorrespondenceLinkRef& c : cut) {
          int i = after.graph.find(c.nodeA, c.nodeB);
          if (i >= 0) after.graph.links.erase(after.graph.links.begin() + i);
        }
        Project trial = doc.project();
        trial.animorphosis = after;
        if (Status s = checkAnimorphosis(trial); !s) {
          status = {s.error(), true};
        } else {
          const std::string label = "Cut " + std::to_string(cut.size()) + " link" + (cut.size() == 1 ? "" : "s");
          doc.execute(setAnimorphosisCommand(doc.project(), std::move(after), label));
          status = {label, false};
          st.selected.reset();
        }
      }
    }
  }
  ImGui::EndChild();

  // Del cuts the selected wire while the editor has the focus.
  if (st.focused && st.selected && !io.WantTextInput &&
      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false)) {
    runCommand(doc, removeCorrespondenceLinkCommand(doc.project(), st.selected->nodeA, st.selected->nodeB), status);
    st.selected.reset();
  }
  ImGui::End();
}

}  // namespace animorph
