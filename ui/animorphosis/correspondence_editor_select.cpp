// The correspondence editor's picking: rows, wires and the selection (correspondence_editor_intern.h).
#include <algorithm>
#include <string>

#include <imgui.h>

#include "core/doc/animorphosis_commands.h"
#include "ui/animorphosis/correspondence_editor_intern.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

constexpr int kDefaultOpenDepth = 3;

void collectRows(const BlobNode& n, int depth, int parent, int shownRow, const std::set<int>& toggled,
                 CorrTreeRows& t) {
  t.parentOf[n.id] = parent;
  if (shownRow < 0) {
    CorrRow r;
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

int countLinksIn(const BlobNode& n, const std::unordered_map<int, int>& direct, CorrTreeRows& t) {
  auto it = direct.find(n.id);
  int count = it == direct.end() ? 0 : it->second;
  for (const BlobNode& c : n.children) count += countLinksIn(c, direct, t);
  t.linksIn[n.id] = count;
  return count;
}

float segmentDistance(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  glm::vec2 ab = b - a;
  float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

// True when segments ab and cd cross.
bool segmentsCross(glm::vec2 a, glm::vec2 b, glm::vec2 c, glm::vec2 d) {
  auto cross = [](glm::vec2 u, glm::vec2 v) { return u.x * v.y - u.y * v.x; };
  const float d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0.0f) != (d2 > 0.0f)) && ((d3 > 0.0f) != (d4 > 0.0f));
}

// The index (CorrWire::link) of the wire within kCorrPickPx of the mouse, the nearest; -1: none.
int nearestWire(const std::vector<CorrWire>& wires, glm::vec2 mouse) {
  int best = -1;
  float bestD = kCorrPickPx;
  for (const CorrWire& w : wires) {
    float d = corrWireDistance(w, mouse);
    if (d <= bestD) bestD = d, best = w.link;
  }
  return best;
}

}  // namespace

CorrTreeRows buildCorrRows(const BlobTree& tree, const std::set<int>& toggled, const CorrespondenceGraph& g,
                           bool sourceSide) {
  CorrTreeRows t;
  collectRows(tree.root, 0, -1, -1, toggled, t);
  std::unordered_map<int, int> direct;
  for (const CorrespondenceLink& l : g.links) ++direct[sourceSide ? l.nodeA : l.nodeB];
  countLinksIn(tree.root, direct, t);
  return t;
}

void keepCorrSelection(CorrespondenceEditorState& st, const AnimorphosisSetup& m) {
  const std::string key = m.sourceActorId + "->" + m.targetActorId;
  if (st.treesKey != key) {
    st.treesKey = key;
    st.toggledA.clear();
    st.toggledB.clear();
    st.selected.reset();
    st.selectedSuggestion.reset();
  }
  if (st.selected && m.graph.find(st.selected->nodeA, st.selected->nodeB) < 0) st.selected.reset();
}

CorrRowHit pressCorrRow(CorrFrame& f, const CorrRow& r, int side, float indentX) {
  CorrespondenceEditorState& st = f.st;
  const BlobNode& n = *r.node;
  const glm::vec2 mouse = f.mouse;
  ImGui::SetCursorScreenPos(ImVec2(r.min.x, r.min.y));
  ImGui::PushID(side * 1000003 + n.id);
  ImGui::InvisibleButton("##row", ImVec2(std::max(1.0f, r.max.x - r.min.x), std::max(1.0f, r.max.y - r.min.y)));
  ImGui::PopID();
  noteWidget(std::string(side == 0 ? "corr/a/" : "corr/b/") + std::to_string(n.id));
  CorrRowHit hit;
  hit.hovered = ImGui::IsItemHovered();
  f.rowHovered |= hit.hovered;
  hit.dropTarget = st.dragSide >= 0 && st.dragSide != side && mouse.x >= r.min.x && mouse.x < r.max.x &&
                   mouse.y >= r.min.y && mouse.y < r.max.y;
  if (hit.hovered || hit.dropTarget) st.hovered = Selection{side == 0 ? f.src.id : f.dst.id, n.id};
  if (ImGui::IsItemClicked(0)) {
    if (!n.children.empty() && mouse.x >= indentX && mouse.x < indentX + kCorrArrowW * f.z) {
      std::set<int>& toggled = side == 0 ? st.toggledA : st.toggledB;
      if (!toggled.erase(n.id)) toggled.insert(n.id);
    } else {  // the node becomes the document's selection (inspector, outliner)
      f.doc.selection = Selection{side == 0 ? f.src.id : f.dst.id, n.id};
    }
  }
  if (ImGui::IsItemActive() && ImGui::IsMouseDragging(0, 4.0f) && st.dragSide < 0) {
    st.dragSide = side;
    st.dragNode = n.id;
  }
  return hit;
}

void clickCorrWires(CorrFrame& f) {
  CorrespondenceEditorState& st = f.st;
  if (!f.graphHovered || f.rowHovered || st.dragSide >= 0 || ImGui::GetIO().KeyCtrl ||
      !(ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1)))
    return;
  const int hit = nearestWire(f.wires, f.mouse);
  const int hitSuggestion = hit >= 0 ? -1 : nearestWire(f.suggestionWires, f.mouse);
  if (hit >= 0) {
    const CorrespondenceLink& l = f.setup.graph.links[size_t(hit)];
    st.selected = CorrespondenceLinkRef{l.nodeA, l.nodeB};
    st.selectedSuggestion.reset();
    if (ImGui::IsMouseClicked(1)) ImGui::OpenPopup("##wire_menu");
  } else if (hitSuggestion >= 0) {
    const CorrespondenceLink& l = f.setup.graph.suggestions[size_t(hitSuggestion)];
    st.selectedSuggestion = CorrespondenceLinkRef{l.nodeA, l.nodeB};
    st.selected.reset();
    if (ImGui::IsMouseDoubleClicked(0)) {
      runCorrCommand(f.doc, acceptSuggestionCommand(f.doc.project(), l.nodeA, l.nodeB), f.status);
      st.selectedSuggestion.reset();
    } else if (ImGui::IsMouseClicked(1)) {
      ImGui::OpenPopup("##suggestion_menu");
    }
  } else if (ImGui::IsMouseClicked(0)) {
    st.selected.reset();
    st.selectedSuggestion.reset();
  }
}

float corrWireDistance(const CorrWire& w, glm::vec2 p) {
  float best = 1e30f;
  glm::vec2 prev = w.p0;
  for (int i = 1; i <= kCorrWireSamples; ++i) {
    glm::vec2 q = w.at(float(i) / kCorrWireSamples);
    best = std::min(best, segmentDistance(p, prev, q));
    prev = q;
  }
  return best;
}

bool corrWireCrossesTrail(const CorrWire& w, const std::vector<glm::vec2>& trail) {
  glm::vec2 prev = w.p0;
  for (int i = 1; i <= kCorrWireSamples; ++i) {
    glm::vec2 q = w.at(float(i) / kCorrWireSamples);
    for (size_t k = 1; k < trail.size(); ++k)
      if (segmentsCross(prev, q, trail[k - 1], trail[k])) return true;
    prev = q;
  }
  return false;
}

}  // namespace animorph
