// The editor side of the animorphosis: Create > Animorphosis..., the
// correspondence editor (link by drag, refused links, cut, auto-map, undo),
// the interval markers on the timeline and the s curves in the curve editor.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <thread>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "ui/animorphosis/animorphosis_panel.h"
#include "demo/animorphosis_demo.h"
#include "core/doc/animorphosis_commands.h"
#include "core/project/animorphosis_project.h"
#include "core/doc/blobtree_commands.h"
#include "core/project/project_io.h"
#include "core/scene/animorphosis_scene.h"
#include "core/anim/key_edit.h"
#include "ui/curves/curve_source.h"
#include "support/editor_fixture.h"
#include "util/animorph_fixtures.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// A document with the walker and the flyer as BlobTree actors "walker" and "flyer", no animorphosis.
void loadCreatures(EditorFixture& f, bool both = true) {
  Project p;
  p.timeline.frameStart = 0;
  p.timeline.frameEnd = 96;
  Actor a = makeBlobTreeActor(p, "walker");
  a.id = "walker";
  a.blobTree = walkerTree();
  p.actors.push_back(a);
  if (both) {
    Actor b = makeBlobTreeActor(p, "flyer");
    b.id = "flyer";
    b.blobTree = flyerTree();
    p.actors.push_back(b);
  }
  f.h.document->reset(p, f.dir.file("creatures.animorph"));
  f.h.frames(2);
}

void openCreateModal(EditorHarness& h) {
  h.clickWidget("menu/Create");
  h.clickWidget("menu/Animorphosis...");
  h.frames(2);
}

// Through the modal: walker -> flyer over frames 24..72, automatic correspondence on or off.
void createThroughModal(EditorHarness& h, bool autoMap) {
  openCreateModal(h);
  REQUIRE(h.hasWidget("animorphosis/create/create"));
  if (!autoMap) h.clickWidget("animorphosis/create/auto");
  h.clickWidget("animorphosis/create/create");
  h.frames(2);
  REQUIRE(h.doc().project().animorphosis.enabled());
}

const CorrespondenceGraph& graph(EditorHarness& h) { return h.doc().project().animorphosis.graph; }

std::string row(int side, int id) { return std::string(side == 0 ? "corr/a/" : "corr/b/") + std::to_string(id); }

void dragLink(EditorHarness& h, int nodeA, int nodeB) {
  h.drag(h.widgetCenter(row(0, nodeA)), h.widgetCenter(row(1, nodeB)), 0, 8);
  h.frames(1);
}

}  // namespace

TEST_CASE("Create > Animorphosis with one BlobTree actor says why", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f, /*both=*/false);
  openCreateModal(f.h);
  CHECK(f.h.hasWidget("animorphosis/create/why"));
  CHECK_FALSE(f.h.hasWidget("animorphosis/create/create"));
  f.h.clickWidget("animorphosis/create/cancel");
  f.h.frames(2);
  CHECK_FALSE(f.h.doc().project().animorphosis.enabled());
  CHECK_FALSE(f.h.doc().history().canUndo());
}

TEST_CASE("Create > Animorphosis is one undoable step with automatic links, and opens the correspondence editor",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/true);
  const AnimorphosisSetup& m = f.h.doc().project().animorphosis;
  CHECK(m.sourceActorId == "walker");
  CHECK(m.targetActorId == "flyer");
  CHECK(m.startSec == Approx(24.0 / f.h.doc().project().timeline.fps));
  CHECK(m.endSec == Approx(72.0 / f.h.doc().project().timeline.fps));
  REQUIRE_FALSE(m.graph.links.empty());
  for (const CorrespondenceLink& l : m.graph.links) CHECK_FALSE(l.artist);
  CHECK(f.h.ui->state().correspondence.visible);
  CHECK(f.h.hasWidget("corr/window"));
  CHECK(f.h.hasWidget(row(0, 2)));
  CHECK(f.h.hasWidget(row(1, 102)));
  // One wire per link, each findable by its nodes.
  for (const CorrespondenceLink& l : m.graph.links)
    CHECK(f.h.hasWidget("corr/link/" + std::to_string(l.nodeA) + "-" + std::to_string(l.nodeB)));
  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(2);
  CHECK_FALSE(f.h.doc().project().animorphosis.enabled());
}

TEST_CASE("correspondence editor: drag links, a refused link reports both nodes, Del cuts, Ctrl+Z restores",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  REQUIRE(graph(f.h).links.empty());
  const size_t steps = f.h.doc().history().index();

  dragLink(f.h, 2, 102);  // walker body -> flyer body
  REQUIRE(graph(f.h).links.size() == 1);
  CHECK(graph(f.h).find(2, 102) == 0);
  CHECK(graph(f.h).links[0].artist);
  CHECK(f.h.doc().history().index() == steps + 1);
  CHECK_FALSE(f.h.ui->state().status.error);

  // belly lies inside body, whose partner is the flyer's body; membraneL does not.
  dragLink(f.h, 3, 106);
  CHECK(graph(f.h).links.size() == 1);
  CHECK(f.h.ui->state().status.error);
  CHECK(f.h.ui->state().status.text.find("belly") != std::string::npos);
  CHECK(f.h.ui->state().status.text.find("membraneL") != std::string::npos);
  CHECK(f.h.doc().history().index() == steps + 1);

  // Dragging from the target side links too.
  f.h.drag(f.h.widgetCenter(row(1, 103)), f.h.widgetCenter(row(0, 3)), 0, 8);
  f.h.frames(1);
  CHECK(graph(f.h).find(3, 103) >= 0);

  // Select the body wire, Del cuts it (the actors stay).
  f.h.clickWidget("corr/link/2-102");
  REQUIRE(f.h.ui->state().correspondence.selected);
  CHECK(f.h.ui->state().correspondence.selected->nodeA == 2);
  f.h.tapKey(GLFW_KEY_DELETE);
  f.h.frames(1);
  CHECK(graph(f.h).find(2, 102) < 0);
  CHECK(f.h.doc().project().actors.size() == 2);
  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(2);
  CHECK(graph(f.h).find(2, 102) >= 0);
}

TEST_CASE("correspondence editor: right-click > Cut, Auto-map keeps the artist's links", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  dragLink(f.h, 2, 102);
  dragLink(f.h, 9, 109);  // the walker's tail becomes the flyer's legs: not what auto-map would say
  REQUIRE(graph(f.h).links.size() == 2);

  f.h.clickWidget("corr/automap");
  f.h.frames(1);
  const CorrespondenceGraph g = graph(f.h);
  CHECK(g.links.size() > 2);
  REQUIRE(g.find(2, 102) >= 0);
  REQUIRE(g.find(9, 109) >= 0);
  CHECK(g.links[size_t(g.find(2, 102))].artist);
  CHECK(g.links[size_t(g.find(9, 109))].artist);
  int automatic = 0;
  for (const CorrespondenceLink& l : g.links) automatic += l.artist ? 0 : 1;
  CHECK(automatic == int(g.links.size()) - 2);

  f.h.click(f.h.widgetCenter("corr/link/9-109"), 1);
  f.h.frames(1);
  REQUIRE(f.h.hasWidget("corr/menu/cut"));
  f.h.clickWidget("corr/menu/cut");
  f.h.frames(1);
  CHECK(graph(f.h).find(9, 109) < 0);
  CHECK(graph(f.h).links.size() == g.links.size() - 1);

  f.h.tapKey(GLFW_KEY_Z, true);  // the cut
  f.h.tapKey(GLFW_KEY_Z, true);  // the auto-map
  f.h.frames(2);
  CHECK(graph(f.h).links.size() == 2);
}

TEST_CASE("the curve editor shows the global s, and a selected link's own s", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  f.h.ui->state().curveEditor.visible = true;
  f.h.frames(2);
  CHECK(f.h.ui->state().curveEditor.sourceId == "animorphosis/-1--1");
  dragLink(f.h, 2, 102);
  f.h.frames(1);
  CHECK(f.h.ui->state().curveEditor.sourceId == "animorphosis/2-102");
  f.h.clickWidget("corr/own_s");
  f.h.frames(1);
  const auto& l = graph(f.h).links[size_t(graph(f.h).find(2, 102))];
  REQUIRE(l.sOverride);
  CHECK(*l.sOverride == f.h.doc().project().animorphosis.globalS);
}

TEST_CASE("the animorphosis interval is a band with two draggable markers on the timeline", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  const double fps = f.h.doc().project().timeline.fps;
  REQUIRE(f.h.hasWidget("timeline/animorphosis/start"));
  REQUIRE(f.h.hasWidget("timeline/animorphosis/end"));
  const glm::vec2 start = f.h.widgetCenter("timeline/animorphosis/start");
  const glm::vec2 end = f.h.widgetCenter("timeline/animorphosis/end");
  const float pxPerFrame = (end.x - start.x) / 48.0f;
  const size_t steps = f.h.doc().history().index();
  f.h.drag(end, end + glm::vec2(12.0f * pxPerFrame, 0.0f), 0, 6);
  f.h.frames(1);
  CHECK(f.h.doc().project().animorphosis.endSec * fps == Approx(84.0).margin(1.0));
  CHECK(f.h.doc().project().animorphosis.startSec * fps == Approx(24.0));
  CHECK(f.h.doc().history().index() == steps + 1);  // the whole drag is one step
  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(1);
  CHECK(f.h.doc().project().animorphosis.endSec * fps == Approx(72.0));
}

TEST_CASE("the viewport's scene shows the source, then C(t), then the target", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/true);
  const Project& p = f.h.doc().project();
  const double fps = p.timeline.fps;
  AnimorphosisCache cache;
  auto sceneAt = [&](double frame, AnimorphosisSceneInfo& info) {
    SceneFrame s = evaluateScene(p, f.h.doc().baseDir(), f.h.assets, frame / fps);
    REQUIRE(s.blobs.size() == 2);
    info = applyAnimorphosis(s, p, cache, &f.h.doc(), f.h.doc().revision());
    return s;
  };
  AnimorphosisSceneInfo info;
  SceneFrame before = sceneAt(12, info);
  CHECK(info.stage == AnimorphosisStage::Source);
  REQUIRE(before.blobs.size() == 1);
  CHECK(before.blobs[0].actorId == "walker");
  CHECK_FALSE(before.blobs[0].source);
  CHECK_FALSE(before.blobs[0].ownTree());
  CHECK(describeAnimorphosis(info) == "animorphosis: source");

  SceneFrame mid = sceneAt(48, info);
  CHECK(info.stage == AnimorphosisStage::Morph);
  CHECK(info.u == Approx(0.5));
  REQUIRE(mid.blobs.size() == 1);
  CHECK(mid.blobs[0].actorId == "walker");
  REQUIRE(mid.blobs[0].source);
  REQUIRE(mid.blobs[0].ownTree());  // the snapshot of C(t), built when asked
  CHECK(mid.blobs[0].ownTree()->root.subtreeSize() == projectGenericTree(p)->size());
  CHECK(mid.blobGuides.get().empty());
  CHECK(describeAnimorphosis(info).rfind("animorphosis u=0.50", 0) == 0);
  // The same time gives the same source and snapshot (the preview is not asked again); another time new ones.
  const std::shared_ptr<const BlobTree> midTree = mid.blobs[0].ownTree();
  SceneFrame again = sceneAt(48, info);
  CHECK(again.blobs[0].source == mid.blobs[0].source);
  CHECK(again.blobs[0].ownTree() == midTree);
  SceneFrame later = sceneAt(60, info);
  CHECK(later.blobs[0].source != mid.blobs[0].source);
  CHECK(later.blobs[0].ownTree() != midTree);

  SceneFrame after = sceneAt(90, info);
  CHECK(info.stage == AnimorphosisStage::Target);
  REQUIRE(after.blobs.size() == 1);
  CHECK(after.blobs[0].actorId == "flyer");
  for (const SceneFrame* s : {&before, &mid, &after}) CHECK(s->blobs[0].opacity == 1.0f);
}

TEST_CASE("the Ghosts checkbox shows A(t) and B(t) translucent and tinted beside C(t), is saved and undoable", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/true);
  CHECK_FALSE(f.h.doc().project().animorphosis.showGhosts);
  f.h.clickWidget("corr/ghosts");
  f.h.frames(1);
  const Project& p = f.h.doc().project();
  REQUIRE(p.animorphosis.showGhosts);
  AnimorphosisCache cache;
  auto sceneAt = [&](double frame, bool ghosts) {
    SceneFrame s = evaluateScene(p, f.h.doc().baseDir(), f.h.assets, frame / p.timeline.fps);
    applyAnimorphosis(s, p, cache, &f.h.doc(), f.h.doc().revision(), ghosts);
    return s;
  };
  SceneFrame mid = sceneAt(48, true);
  REQUIRE(mid.blobs.size() == 3);  // C, then the two ghosts with their own trees at their own times
  CHECK(mid.blobs[0].source);
  CHECK(mid.blobs[0].opacity == 1.0f);
  CHECK(mid.blobs[1].actorId == "walker");
  CHECK(mid.blobs[1].key() == "walker#ghost");
  CHECK(mid.blobs[2].key() == "flyer#ghost");
  for (int i : {1, 2}) {
    CHECK(mid.blobs[size_t(i)].opacity == Approx(kGhostOpacity));
    CHECK_FALSE(mid.blobs[size_t(i)].source);
  }
  // Tinted apart from C (the clay tone) and from each other: the source blue, the target orange.
  CHECK_FALSE(mid.blobs[0].tint);
  REQUIRE(mid.blobs[1].tint);
  REQUIRE(mid.blobs[2].tint);
  CHECK(*mid.blobs[1].tint == kGhostSourceTint);
  CHECK(*mid.blobs[2].tint == kGhostTargetTint);
  CHECK(kGhostSourceTint.b > kGhostSourceTint.r);
  CHECK(kGhostTargetTint.r > kGhostTargetTint.b);
  CHECK(sceneAt(48, false).blobs.size() == 1);  // the CLI's renders and bakes ask for none
  CHECK(sceneAt(12, true).blobs.size() == 1);   // outside the interval the actor is itself
  // Saved in the project's animorphosis section.
  auto back = projectFromJson(projectToJson(p), "ghosts.animorph");
  REQUIRE(back.ok());
  CHECK(back->animorphosis.showGhosts);
  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(2);
  CHECK_FALSE(f.h.doc().project().animorphosis.showGhosts);
}

TEST_CASE("correspondence editor: a Ctrl+right-drag across wires cuts them in one undo step", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  dragLink(f.h, 2, 102);
  dragLink(f.h, 9, 112);
  dragLink(f.h, 12, 104);  // refused (the head is outside the body, the chest inside the flyer's body): no wire
  REQUIRE(graph(f.h).links.size() == 2);
  const size_t steps = f.h.doc().history().index();
  const glm::vec2 body = f.h.widgetCenter("corr/link/2-102");
  const glm::vec2 tail = f.h.widgetCenter("corr/link/9-112");
  // A vertical stroke through both wires' middles.
  const glm::vec2 from(body.x, std::min(body.y, tail.y) - 20.0f), to(body.x, std::max(body.y, tail.y) + 20.0f);
  f.h.setModifiers(true);
  f.h.drag(from, to, 1, 10);
  f.h.setModifiers(false);
  f.h.frames(1);
  CHECK(graph(f.h).links.empty());
  CHECK(f.h.doc().history().index() == steps + 1);
  CHECK_FALSE(f.h.ui->state().status.error);
  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(1);
  CHECK(graph(f.h).links.size() == 2);
}

TEST_CASE("hovering a node in the correspondence editor asks the viewport to highlight it", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  f.h.moveTo(f.h.widgetCenter(row(1, 105)));
  f.h.frames(1);
  CHECK(f.h.ui->output().highlightBlobNode == Selection{"flyer", 105});
  f.h.moveTo(f.h.widgetCenter("corr/automap"));
  f.h.frames(1);
  CHECK(f.h.ui->output().highlightBlobNode.actorId.empty());
}

TEST_CASE("the animorphosis curve source edits the global s and a link's own s, and refuses a broken s curve",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  dragLink(f.h, 2, 102);
  f.h.clickWidget("corr/own_s");
  f.h.frames(1);
  auto src = makeAnimorphosisCurveSource(f.h.doc(), 2, 102);
  REQUIRE(src);
  const std::vector<CurveChannel> channels = src->channels();
  REQUIRE(channels.size() == 2);  // the global s and the link's own
  const ParamAddress link = channels[1].addr;
  const size_t keys = f.h.doc().project().animorphosis.graph.links[0].sOverride->keys().size();
  // A key at u = 0.3 on the link's curve, raised to 0.8: wings that grow fast.
  auto cmd = src->edit("Key s", [&](const TrackSet& set) -> Status {
    auto k = insertKey(set, link, 0.3);
    if (!k) return Error{k.error()};
    auto moved = setKeyTimeValue(set, {{link, *k}, 0}, 0.3, 0.8f);
    return moved ? Status::success() : Status(Error{moved.error()});
  });
  REQUIRE(cmd);
  f.h.doc().execute(std::move(*cmd));
  const FloatTrack& s = *f.h.doc().project().animorphosis.graph.links[0].sOverride;
  CHECK(s.keys().size() == keys + 1);
  CHECK(s.evaluate(0.3) == Approx(0.8f));
  CHECK(f.h.doc().project().animorphosis.globalS == defaultSCurve());
  // Moving the global s's last key off (1, 1) is refused, naming the curve.
  const FloatTrack& g = f.h.doc().project().animorphosis.globalS;
  const int last = int(g.keys().size()) - 1;
  auto broken = src->edit("Move key", [&](const TrackSet& set) -> Status {
    auto moved = setKeyTimeValue(set, {{channels[0].addr, last}, 0}, 1.0, 0.5f);
    return moved ? Status::success() : Status(Error{moved.error()});
  });
  REQUIRE_FALSE(broken);
  CHECK(broken.error().find("global s") != std::string::npos);
}

namespace {
// The last node of tree shown as a row by default (pre-order, the top three levels open).
int lastDefaultRow(const BlobNode& n, int depth = 0) {
  int last = n.id;
  if (depth < 3)
    for (const BlobNode& c : n.children) last = lastDefaultRow(c, depth + 1);
  return last;
}
WidgetRect rectOf(EditorHarness& h, const std::string& key) {
  auto r = h.ui->widgets().find(key);
  REQUIRE(r);
  return *r;
}
}  // namespace

TEST_CASE("correspondence editor: the wheel zooms around the mouse, a middle drag pans, F frames all, links still land",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  const CorrespondenceEditorState& st = f.h.ui->state().correspondence;
  const WidgetRect before = rectOf(f.h, row(0, 2));
  const float h0 = before.max.y - before.min.y;

  // Two notches up half-way between the two bodies' rows: rows grow around the mouse (the point
  // half-way between the two rows stays under it).
  const glm::vec2 at = 0.5f * (before.center() + rectOf(f.h, row(1, 102)).center());
  f.h.wheel(at, 2.0f);
  f.h.frames(2);
  CHECK(st.zoom > 1.3f);
  const WidgetRect zoomed = rectOf(f.h, row(0, 2));
  CHECK(zoomed.max.y - zoomed.min.y == Approx(h0 * st.zoom).margin(1.0));
  const glm::vec2 mid = 0.5f * (zoomed.center() + rectOf(f.h, row(1, 102)).center());
  CHECK(mid.x == Approx(at.x).margin(1.5));
  CHECK(mid.y == Approx(at.y).margin(1.5));

  // A link dragged in the zoomed view joins the rows under the mouse.
  dragLink(f.h, 2, 102);
  CHECK(graph(f.h).find(2, 102) >= 0);
  CHECK(graph(f.h).links.size() == 1);

  // A middle drag moves the rows with the mouse.
  const glm::vec2 c0 = rectOf(f.h, row(0, 3)).center();
  f.h.drag(c0, c0 + glm::vec2(40.0f, -30.0f), 2, 6);
  f.h.frames(1);
  const glm::vec2 c1 = rectOf(f.h, row(0, 3)).center();
  CHECK(c1.x - c0.x == Approx(40.0f).margin(2.0f));
  CHECK(c1.y - c0.y == Approx(-30.0f).margin(2.0f));
  dragLink(f.h, 3, 103);  // panned, links still land
  CHECK(graph(f.h).find(3, 103) >= 0);

  // F (the editor has the focus): every row fits in the window again.
  f.h.tapKey(GLFW_KEY_F);
  f.h.frames(2);
  CHECK(st.zoom < 1.3f);
  const WidgetRect window = rectOf(f.h, "corr/window");
  for (const auto& [side, tree] : {std::pair{0, walkerTree()}, std::pair{1, flyerTree()}}) {
    const WidgetRect last = rectOf(f.h, row(side, lastDefaultRow(tree.root)));
    CHECK(last.max.y <= window.max.y);
    CHECK(last.min.x >= window.min.x);
    CHECK(last.max.x <= window.max.x);
  }
  CHECK(rectOf(f.h, row(0, 2)).min.y >= window.min.y);
}

TEST_CASE("Animorphosis > Bake to Key-frame Actor adds one key-framed BlobTree actor, reports the keys, Ctrl+Z removes it",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/true);
  const size_t actors = f.h.doc().project().actors.size();
  f.h.clickWidget("menu/Animorphosis");
  f.h.clickWidget("menu/Bake to Key-frame Actor");
  f.h.frames(3);  // the bake runs as the background job; its result is applied on the UI thread
  INFO(f.h.ui->state().status.text);
  REQUIRE(f.h.doc().project().actors.size() == actors + 1);
  const Actor& baked = f.h.doc().project().actors.back();
  CHECK(baked.kind == ActorKind::BlobTree);
  CHECK(baked.name == "walker -> flyer (keys)");
  CHECK(baked.blobTree.root.subtreeSize() > walkerTree().root.subtreeSize());
  CHECK(f.h.doc().selection.actorId == baked.id);
  CHECK_FALSE(f.h.ui->state().status.error);
  CHECK(f.h.ui->state().status.text.find("nA + nB + ns") != std::string::npos);
  CHECK(f.h.ui->state().status.text.find("largest deviation") != std::string::npos);

  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(2);
  CHECK(f.h.doc().project().actors.size() == actors);

  // The correspondence editor's button does the same.
  f.h.clickWidget("corr/bake_keys");
  f.h.frames(3);
  CHECK(f.h.doc().project().actors.size() == actors + 1);
}

TEST_CASE("Bake to Key-frame Actor on the demo: Cancel stops the bake part-way and adds nothing", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  auto demo = makeAnimorphosisDemoProject();
  INFO(demo.error());
  REQUIRE(demo.ok());
  f.h.document->reset(*demo, f.dir.file("demo.animorph"));
  f.h.frames(2);
  const size_t actors = f.h.doc().project().actors.size();
  const uint64_t revision = f.h.doc().revision();
  f.h.finishJobs = false;  // the bake runs on while the person reaches for Cancel
  f.h.clickWidget("menu/Animorphosis");
  f.h.clickWidget("menu/Bake to Key-frame Actor");
  const BackgroundJob* job = f.h.ui->runningJob();
  REQUIRE(job);
  REQUIRE(f.h.hasWidget("job/cancel"));  // the job's panel offers Cancel
  // Once the first nodes of C are baked (the progress counts them), what Cancel does, at once: a
  // click takes frames the whole bake may not need.
  while (!job->finished() && job->progress().done() < 1.0) std::this_thread::sleep_for(std::chrono::microseconds(200));
  f.h.ui->cancelJob();
  // The bake polls the flag before every channel: it returns long before it would have finished.
  while (!job->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const double done = job->progress().done(), total = job->progress().total();
  INFO("nodes baked " << done << " of " << total);
  CHECK(total >= 7000.0);  // C's nodes
  CHECK(done >= 1.0);
  CHECK(done < total);
  f.h.ui->finishJob(f.h.ctx);
  f.h.finishJobs = true;
  f.h.frames(2);
  CHECK(f.h.ui->state().status.text.find("cancelled") != std::string::npos);
  CHECK(f.h.doc().project().actors.size() == actors);
  CHECK(f.h.doc().revision() == revision);
}

namespace {

// Vertices of the last frame's draw data in colour `col`.
int verticesOfColor(ImU32 col) {
  const ImDrawData* d = ImGui::GetDrawData();
  int n = 0;
  for (int i = 0; d && i < d->CmdListsCount; ++i)
    for (const ImDrawVert& v : d->CmdLists[i]->VtxBuffer) n += v.col == col ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("correspondence editor: suggestions are dashed violet wires, Accept applies one, Accept all the rest, "
          "each undoable",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  {
    AnimorphosisSetup m = f.h.doc().project().animorphosis;
    m.graph.suggestions.push_back({2, 102, {}, 0.3f, false});   // body -> body
    m.graph.suggestions.push_back({9, 112, {}, 0.25f, false});  // tail -> tail
    m.graph.suggestions.push_back({3, 106, {}, 0.1f, false});   // belly -> membraneL: breaks a rule once 2 -> 102 is in
    f.h.doc().execute(setAnimorphosisCommand(f.h.doc().project(), m, "suggest"));
  }
  f.h.frames(2);
  // Drawn apart from the links: each has its own widget and no link wire, in the suggestion colour.
  REQUIRE(f.h.hasWidget("corr/suggestion/2-102"));
  REQUIRE(f.h.hasWidget("corr/suggestion/9-112"));
  CHECK_FALSE(f.h.hasWidget("corr/link/2-102"));
  CHECK(graph(f.h).links.empty());
  CHECK(verticesOfColor(ImU32(kSuggestionWireColor)) > 0);
  const size_t steps = f.h.doc().history().index();

  // Select one by clicking its wire, accept it: an artist link, no longer a suggestion.
  f.h.clickWidget("corr/suggestion/2-102");
  f.h.frames(1);
  REQUIRE(f.h.ui->state().correspondence.selectedSuggestion);
  REQUIRE(f.h.hasWidget("corr/accept"));
  f.h.clickWidget("corr/accept");
  f.h.frames(2);
  REQUIRE(graph(f.h).find(2, 102) >= 0);
  CHECK(graph(f.h).links[size_t(graph(f.h).find(2, 102))].artist);
  CHECK(graph(f.h).findSuggestion(2, 102) < 0);
  CHECK(f.h.hasWidget("corr/link/2-102"));
  CHECK_FALSE(f.h.hasWidget("corr/suggestion/2-102"));
  CHECK(f.h.doc().history().index() == steps + 1);

  // Accept all: the tail is applied; belly -> membraneL would break the hierarchy and stays a suggestion.
  f.h.clickWidget("corr/accept_all");
  f.h.frames(2);
  CHECK(graph(f.h).find(9, 112) >= 0);
  CHECK(graph(f.h).find(3, 106) < 0);
  CHECK(graph(f.h).findSuggestion(3, 106) >= 0);
  CHECK(f.h.ui->state().status.text.find("stay suggestions") != std::string::npos);
  CHECK(f.h.doc().history().index() == steps + 2);

  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(2);
  CHECK(graph(f.h).links.empty());
  CHECK(graph(f.h).suggestions.size() == 3);
  CHECK(f.h.hasWidget("corr/suggestion/2-102"));
}

TEST_CASE("correspondence editor: Auto-map runs as a background job with progress, then applies its links as one "
          "undo step",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  createThroughModal(f.h, /*autoMap=*/false);
  dragLink(f.h, 2, 102);
  REQUIRE(graph(f.h).links.size() == 1);
  const size_t steps = f.h.doc().history().index();
  f.h.finishJobs = false;  // the person sees the job before its result
  f.h.clickWidget("corr/automap");
  // The button started a job; the graph is not touched on the UI thread.
  const BackgroundJob* job = f.h.ui->runningJob();
  REQUIRE(job);
  CHECK(job->label() == "Auto-map");
  CHECK(f.h.hasWidget("job/progress"));
  CHECK(f.h.hasWidget("job/cancel"));
  while (!job->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CHECK(graph(f.h).links.size() == 1);
  // Progress counted the levels against the source's nodes, and ended complete.
  CHECK(job->progress().total() == Approx(double(walkerTree().root.subtreeSize())));
  CHECK(job->progress().done() == Approx(job->progress().total()));
  f.h.frames(1);  // the next frame applies the result
  CHECK_FALSE(f.h.ui->runningJob());
  f.h.finishJobs = true;
  INFO(f.h.ui->state().status.text);
  const CorrespondenceGraph g = graph(f.h);
  CHECK(g.links.size() > 1);
  REQUIRE(g.find(2, 102) >= 0);
  CHECK(g.links[size_t(g.find(2, 102))].artist);
  // The walker's tail is the flyer's tail (ids 9 and 112 in the demo trees' naming).
  CHECK(g.find(9, 112) >= 0);
  CHECK(f.h.ui->state().status.text.find("Auto-map correspondence") != std::string::npos);
  CHECK(f.h.ui->state().status.text.find("proposed") != std::string::npos);
  CHECK(f.h.doc().history().index() == steps + 1);
  for (const CorrespondenceLink& l : g.links)
    CHECK(f.h.hasWidget("corr/link/" + std::to_string(l.nodeA) + "-" + std::to_string(l.nodeB)));
  f.h.tapKey(GLFW_KEY_Z, true);
  f.h.frames(2);
  CHECK(graph(f.h).links.size() == 1);
}

TEST_CASE("correspondence editor: Auto-map on the demo, cancelled, leaves the graph untouched", "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  auto demo = makeAnimorphosisDemoProject();
  INFO(demo.error());
  REQUIRE(demo.ok());
  f.h.document->reset(*demo, f.dir.file("demo.animorph"));
  f.h.ui->state().correspondence.visible = true;
  f.h.frames(2);
  REQUIRE(f.h.hasWidget("corr/automap"));
  const CorrespondenceGraph before = graph(f.h);
  const uint64_t revision = f.h.doc().revision();
  f.h.finishJobs = false;
  f.h.clickWidget("corr/automap");
  const BackgroundJob* job = f.h.ui->runningJob();
  REQUIRE(job);
  REQUIRE(f.h.hasWidget("job/cancel"));
  // What Cancel (or Esc) does, at once: a click takes frames the matching may not need. However far
  // the matching got, its result is not applied.
  f.h.ui->cancelJob();
  while (!job->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::printf("Auto-map on the demo cancelled after %.0f of %.0f levels\n", job->progress().done(),
              job->progress().total());
  f.h.ui->finishJob(f.h.ctx);
  f.h.finishJobs = true;
  f.h.frames(2);
  CHECK(f.h.ui->state().status.text.find("Auto-map cancelled") != std::string::npos);
  CHECK(graph(f.h) == before);
  CHECK(f.h.doc().revision() == revision);
  CHECK_FALSE(f.h.doc().history().canUndo());

  // Run again to the end, it applies a graph (one undo step).
  f.h.clickWidget("corr/automap");
  f.h.frames(2);
  INFO(f.h.ui->state().status.text);
  CHECK_FALSE(f.h.ui->state().status.error);
  CHECK(f.h.doc().history().canUndo());
  CHECK(graph(f.h).links.size() > 0);
}

TEST_CASE("Create > Animorphosis with automatic correspondence proposes the graph as a job, and Cancel creates nothing",
          "[animorphosis_ui]") {
  EditorFixture f({1600.0f, 1200.0f});
  loadCreatures(f);
  openCreateModal(f.h);
  REQUIRE(f.h.hasWidget("animorphosis/create/create"));
  f.h.finishJobs = false;
  f.h.clickWidget("animorphosis/create/create");
  const BackgroundJob* job = f.h.ui->runningJob();
  REQUIRE(job);
  CHECK(job->label() == "Create animorphosis");  // its panel (progress, Cancel) is drawn from the next frame
  CHECK_FALSE(f.h.doc().project().animorphosis.enabled());  // nothing yet on the UI thread
  f.h.ui->cancelJob();
  while (!job->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  f.h.ui->finishJob(f.h.ctx);
  f.h.finishJobs = true;
  f.h.frames(2);
  CHECK(f.h.ui->state().status.text.find("cancelled") != std::string::npos);
  CHECK_FALSE(f.h.doc().project().animorphosis.enabled());
  CHECK_FALSE(f.h.doc().history().canUndo());
  CHECK_FALSE(f.h.ui->state().correspondence.visible);
}
