#include <catch2/catch.hpp>

#include <algorithm>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "core/blobtree/tree_edit.h"
#include "ui/curves/curve_editor_panel.h"
#include "editor/selection_info.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// A new BlobTree actor through the outliner button; returns its id.
std::string newBlob(EditorHarness& h) {
  h.clickWidget("outliner/new_blob");
  const Actor* a = blobActor(h);
  REQUIRE(a);
  h.frames(2);
  return a->id;
}

int sphereOf(EditorHarness& h) { return blobActor(h)->blobTree.root.children[0].id; }

ParamAddress radiusOf(EditorHarness&, int node) {
  return {node, paramIndex(NodeType::Sphere, "radius"), -1};
}

float radiusAtFrame(EditorHarness& h, int node, int frame) {
  return blobActor(h)->blobTree.find(node)->floatParam("radius").evaluate(frame / h.doc().project().timeline.fps);
}

void goToFrame(EditorHarness& h, int frame) {
  h.doc().setCurrentFrame(frame);
  h.frames(2);
}

// Selects the sphere, keys its radius at frames 0 and 24, and makes the value at 24 larger by dragging the field.
void keyRadiusTwice(EditorHarness& h, const std::string& id) {
  int s = sphereOf(h);
  h.clickWidget("outliner/" + id + "/blob/" + std::to_string(s));
  REQUIRE(h.doc().selection.node == s);
  goToFrame(h, 0);
  h.clickWidget("inspector/blob/radius/key");
  goToFrame(h, 24);
  h.clickWidget("inspector/blob/radius/key");
  REQUIRE(keyCount(blobActor(h)->blobTree, radiusOf(h, s)) == 2);
  auto r = *h.ui->widgets().find("inspector/blob/radius");
  glm::vec2 c{r.min.x + 20.0f, r.center().y};  // inside the field, left of its label
  h.drag(c, c + glm::vec2(60.0f, 0.0f), 0, 6);
}

// The x of each key-frame diamond the timeline ruler drew in the last frame, left to right: the
// vertices of the draw lists in the key ticks' colour (ui/timeline/timeline_panel.cpp) inside the
// ruler, grouped by position (a diamond's vertices lie within 5 px of its centre).
std::vector<float> drawnKeyTicks(const WidgetRect& ruler) {
  const ImU32 kKeyTickColour = IM_COL32(240, 200, 60, 255);
  std::vector<float> xs;
  const ImDrawData* dd = ImGui::GetDrawData();
  REQUIRE(dd);
  for (int l = 0; l < dd->CmdListsCount; ++l)
    for (const ImDrawVert& v : dd->CmdLists[l]->VtxBuffer)
      if (v.col == kKeyTickColour && v.pos.x >= ruler.min.x - 6.0f && v.pos.x <= ruler.max.x + 6.0f &&
          v.pos.y >= ruler.min.y && v.pos.y <= ruler.max.y)
        xs.push_back(v.pos.x);
  std::sort(xs.begin(), xs.end());
  std::vector<float> ticks;
  for (size_t i = 0; i < xs.size();) {
    size_t j = i;
    while (j < xs.size() && xs[j] - xs[i] <= 10.0f) ++j;
    ticks.push_back(0.5f * (xs[i] + xs[j - 1]));  // the diamond is symmetric about its centre
    i = j;
  }
  return ticks;
}

}  // namespace

TEST_CASE("a node added from the Create menu lands under the selected node", "[ui][blobtree]") {
  EditorFixture f;
  auto& h = f.h;
  std::string id = newBlob(h);
  CHECK(h.doc().selection.actorId == id);
  CHECK(h.doc().history().size() == 1);
  int root = blobActor(h)->blobTree.root.id;
  h.clickWidget("outliner/" + id + "/blob/" + std::to_string(root));
  REQUIRE(h.doc().selection.node == root);

  h.clickWidget("menu/Create");
  h.moveTo(h.widgetCenter("menu/Add/Primitive"));
  h.frames(2);
  REQUIRE(h.hasWidget("menu/Add/point"));
  h.clickWidget("menu/Add/point");
  const BlobTree& t = blobActor(h)->blobTree;
  REQUIRE(t.root.children.size() == 2);
  CHECK(t.root.children[1].type == NodeType::Point);
  CHECK(h.doc().selection.node == t.root.children[1].id);  // the new node is selected
  CHECK(h.doc().history().undoLabel() == "Add point");
  // It shows in the outliner, and Ctrl+D duplicates it, Del deletes the copy.
  h.frames(1);
  CHECK(h.hasWidget("outliner/" + id + "/blob/" + std::to_string(t.root.children[1].id)));
  h.tapKey(GLFW_KEY_D, true);
  CHECK(blobActor(h)->blobTree.root.children.size() == 3);
  h.tapKey(GLFW_KEY_DELETE);
  CHECK(blobActor(h)->blobTree.root.children.size() == 2);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(blobActor(h)->blobTree.root.children.size() == 3);
}

TEST_CASE("dragging a node onto another in the outliner reparents it, cycles are refused", "[ui][blobtree]") {
  EditorFixture f;
  auto& h = f.h;
  std::string id = newBlob(h);
  int root = blobActor(h)->blobTree.root.id;
  h.clickWidget("outliner/" + id + "/blob/" + std::to_string(root));
  h.clickWidget("menu/Create");
  h.moveTo(h.widgetCenter("menu/Add/Space map"));
  h.frames(2);
  h.clickWidget("menu/Add/frame");
  int frame = blobActor(h)->blobTree.root.children[1].id;
  int sphere = sphereOf(h);
  h.frames(2);
  auto key = [&](int n) { return "outliner/" + id + "/blob/" + std::to_string(n); };
  INFO("sphere row " << h.widgetCenter(key(sphere)).y << ", frame row " << h.widgetCenter(key(frame)).y);
  h.drag(h.widgetCenter(key(sphere)), h.widgetCenter(key(frame)), 0, 10);
  const BlobTree& t = blobActor(h)->blobTree;
  INFO("status: " << h.ui->state().status.text << "; selected node " << h.doc().selection.node);
  REQUIRE(t.find(frame)->children.size() == 2);
  CHECK(t.find(frame)->children[1].id == sphere);
  CHECK(t.root.children.size() == 1);
  // The frame onto its own child: refused, nothing changes, the status says why.
  size_t steps = h.doc().history().size();
  h.frames(2);
  int frameChild = t.find(frame)->children[0].id;
  h.drag(h.widgetCenter(key(frame)), h.widgetCenter(key(frameChild)), 0, 10);
  CHECK(h.doc().history().size() == steps);
  CHECK(h.ui->state().status.error);
  CHECK_THAT(h.ui->state().status.text, Catch::Contains("cycle"));
}

TEST_CASE("a parameter keyed at two frames interpolates when the current frame changes", "[ui][blobtree]") {
  EditorFixture f;
  auto& h = f.h;
  std::string id = newBlob(h);
  keyRadiusTwice(h, id);
  int s = sphereOf(h);
  float r0 = radiusAtFrame(h, s, 0), r24 = radiusAtFrame(h, s, 24);
  CHECK(r24 > r0 + 0.05f);  // the drag changed the key at 24, not the one at 0
  CHECK(keyCount(blobActor(h)->blobTree, radiusOf(h, s)) == 2);
  // At frame 12 the value lies between the keys; the timeline shows both key ticks.
  goToFrame(h, 12);
  float r12 = radiusAtFrame(h, s, 12);
  CHECK(r12 > r0);
  CHECK(r12 < r24);
  CHECK(h.hasWidget("inspector/blob/radius"));
  // The drag was one undo step.
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(radiusAtFrame(h, s, 24) == Approx(r0));
}

TEST_CASE("a curve editor key drag is one undo step, snapped to whole frames", "[ui][blobtree][curves]") {
  EditorFixture f;
  auto& h = f.h;
  std::string id = newBlob(h);
  keyRadiusTwice(h, id);
  h.tapKey(GLFW_KEY_G, true);  // View > Curve Editor
  h.frames(3);
  const CurveEditorState& ce = h.ui->state().curveEditor;
  REQUIRE(ce.visible);
  REQUIRE(h.hasWidget("curve/graph"));
  int s = sphereOf(h);
  ParamAddress radius = radiusOf(h, s);
  size_t steps = h.doc().history().size();
  glm::vec2 key24 = curveToPixel(ce, 24.0, radiusAtFrame(h, s, 24));
  glm::vec2 pxPerFrame = curveToPixel(ce, 1.0, 0.0) - curveToPixel(ce, 0.0, 0.0);
  // Drag the key at 24 about 5.4 frames to the right and a bit up.
  h.drag(key24, key24 + glm::vec2(pxPerFrame.x * 5.4f, -20.0f), 0, 8);
  CHECK(h.doc().history().size() == steps + 1);
  CHECK(h.doc().history().undoLabel() == "Move key");
  double t = 0.0;
  ParamSample v;
  REQUIRE(keyAt(blobActor(h)->blobTree, {radius, 1}, t, v));
  double fps = h.doc().project().timeline.fps;
  CHECK(t * fps == Approx(29.0).margin(1e-6));  // whole frames
  CHECK(std::get<float>(v) > radiusAtFrame(h, s, 0));
  CHECK(ce.selection.size() == 1);
  h.tapKey(GLFW_KEY_Z, true);
  REQUIRE(keyAt(blobActor(h)->blobTree, {radius, 1}, t, v));
  CHECK(t * fps == Approx(24.0).margin(1e-6));
}

TEST_CASE("curve editor: box select then Del deletes the keys, not the node", "[ui][blobtree][curves]") {
  EditorFixture f;
  auto& h = f.h;
  std::string id = newBlob(h);
  keyRadiusTwice(h, id);
  h.tapKey(GLFW_KEY_G, true);
  h.frames(3);
  const CurveEditorState& ce = h.ui->state().curveEditor;
  int s = sphereOf(h);
  size_t steps = h.doc().history().size();
  // A box over the whole graph catches both keys.
  h.drag(ce.graphMin + glm::vec2(3.0f), ce.graphMax - glm::vec2(3.0f), 0, 6);
  CHECK(ce.selection.size() == 2);
  CHECK(h.doc().history().size() == steps);  // selecting is not an edit
  h.tapKey(GLFW_KEY_DELETE);
  CHECK(h.doc().history().size() == steps + 1);
  CHECK(h.doc().history().undoLabel() == "Delete 2 keys");
  const BlobTree& t = blobActor(h)->blobTree;
  REQUIRE(t.find(s));  // the node is still there
  CHECK(keyCount(t, radiusOf(h, s)) == 1);
  CHECK(ce.selection.empty());
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(keyCount(blobActor(h)->blobTree, radiusOf(h, s)) == 2);
}

TEST_CASE("the timeline shows the selected node's key frames", "[ui][blobtree]") {
  EditorFixture f;
  auto& h = f.h;
  std::string id = newBlob(h);
  keyRadiusTwice(h, id);
  std::vector<int> keys = selectionKeyFrames(h.doc(), h.assets);
  CHECK(keys == std::vector<int>{0, 24});
  // The ruler draws a diamond at each of them, where the ruler maps that frame.
  h.frames(1);
  const WidgetRect ruler = *h.ui->widgets().find("timeline/ruler");
  const TimelineState& view = h.ui->state().timeline;
  const double pxPerFrame = (ruler.max.x - ruler.min.x) / (view.viewEndFrame - view.viewStartFrame);
  const std::vector<float> ticks = drawnKeyTicks(ruler);
  REQUIRE(ticks.size() == keys.size());
  for (size_t i = 0; i < keys.size(); ++i) {
    INFO("key frame " << keys[i]);
    CHECK(ticks[i] == Approx(ruler.min.x + (keys[i] - view.viewStartFrame) * pxPerFrame).margin(1.0));
  }
  // With nothing selected the ruler shows no key.
  h.doc().selection = {};
  h.frames(1);
  CHECK(drawnKeyTicks(ruler).empty());
}
