#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/animorphosis/bake_keys.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/doc/animorphosis_bake_actor.h"
#include "core/doc/animorphosis_commands.h"
#include "core/project/animorphosis_project.h"
#include "core/doc/blobtree_commands.h"
#include "core/doc/document.h"
#include "core/project/project_io.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "demo/animorphosis_demo.h"
#include "core/util/job_progress.h"
#include "util/animorph_fixtures.h"
#include "util/temp_dir.h"

using namespace animorph;
using namespace animorph::test;
using Catch::Matchers::Contains;

namespace {

// A document with the walker and the flyer as BlobTree actors "walker" and "flyer".
std::unique_ptr<Document> creaturesDocument() {
  Project p;
  Actor w = makeBlobTreeActor(p, "walker");
  w.blobTree = walkerTree();
  p.actors.push_back(w);
  Actor f = makeBlobTreeActor(p, "flyer");
  f.blobTree = flyerTree();
  f.timeOffsetSec = 0.5;
  p.actors.push_back(f);
  auto d = std::make_unique<Document>();
  d->reset(p, "");
  return d;
}

void exec(Document& d, Result<std::unique_ptr<Command>> c) {
  INFO(c.error());
  REQUIRE(c.ok());
  d.execute(std::move(*c));
}

}  // namespace

TEST_CASE("animorphosis: created, edited and undone through document commands", "[animorph]") {
  auto doc = creaturesDocument();
  REQUIRE(doc->project().findActor("walker"));
  REQUIRE(doc->project().findActor("flyer"));

  auto refused = createAnimorphosisCommand(doc->project(), "walker", "nobody", 1.0, 3.0, true);
  REQUIRE_FALSE(refused.ok());
  CHECK_THAT(refused.error(), Contains("'nobody'"));
  CHECK_FALSE(createAnimorphosisCommand(doc->project(), "walker", "flyer", 3.0, 1.0, true).ok());

  exec(*doc, createAnimorphosisCommand(doc->project(), "walker", "flyer", 1.0, 3.0, true));
  const AnimorphosisSetup& a = doc->project().animorphosis;
  CHECK(a.enabled());
  size_t autoLinks = a.graph.links.size();
  CHECK(autoLinks >= 5);
  CHECK(std::none_of(a.graph.links.begin(), a.graph.links.end(), [](const auto& l) { return l.artist; }));

  // An artist link, then a crossing one, refused naming both nodes.
  exec(*doc, addCorrespondenceLinkCommand(doc->project(), 12, 105));  // head -> left wing
  CHECK(doc->project().animorphosis.graph.find(12, 105) >= 0);
  auto crossing = addCorrespondenceLinkCommand(doc->project(), 6, 103);  // a thigh -> the belly, inside the body
  REQUIRE_FALSE(crossing.ok());
  CHECK_THAT(crossing.error(), Contains("'thighL' (id 6)") && Contains("'belly' (id 103)"));

  auto headLink = [&]() -> const CorrespondenceLink& {
    const auto& gr = doc->project().animorphosis.graph;
    return gr.links[size_t(gr.find(12, 105))];
  };
  exec(*doc, setLinkSOverrideCommand(doc->project(), 12, 105, hermiteRampTrack(0.0f, 2.0f)));
  CHECK(headLink().sOverride.has_value());
  CHECK_FALSE(setGlobalSCommand(doc->project(), FloatTrack(0.5f)).ok());  // not an s curve
  exec(*doc, setAnimorphosisIntervalCommand(doc->project(), 0.5, 2.5));

  // Auto-map again keeps the artist link.
  AutoCorrespondReport report;
  exec(*doc, autoMapCommand(doc->project(), {}, &report));
  CHECK(report.artistKept == 1);
  const auto& g = doc->project().animorphosis.graph;
  REQUIRE(g.find(12, 105) >= 0);
  CHECK(g.links[size_t(g.find(12, 105))].artist);
  CHECK(g.links[size_t(g.find(12, 105))].sOverride.has_value());

  // Undo walks back through every step.
  REQUIRE(doc->undo());  // auto-map
  REQUIRE(doc->undo());  // interval
  CHECK(doc->project().animorphosis.startSec == 1.0);
  REQUIRE(doc->undo());  // s override
  CHECK_FALSE(headLink().sOverride.has_value());
  REQUIRE(doc->undo());  // artist link
  CHECK(doc->project().animorphosis.graph.find(12, 105) < 0);
  CHECK(doc->project().animorphosis.graph.links.size() == autoLinks);
  REQUIRE(doc->undo());  // creation
  CHECK_FALSE(doc->project().animorphosis.enabled());
  REQUIRE(doc->redo());
  CHECK(doc->project().animorphosis.graph.links.size() == autoLinks);
}

TEST_CASE("animorphosis: saved in the project file and read back, bad sections are refused by name", "[animorph]") {
  auto doc = creaturesDocument();
  exec(*doc, createAnimorphosisCommand(doc->project(), "walker", "flyer", 1.0, 3.0, true));
  exec(*doc, addCorrespondenceLinkCommand(doc->project(), 12, 105));
  exec(*doc, setLinkSOverrideCommand(doc->project(), 12, 105, hermiteRampTrack(2.0f, 0.0f)));
  TempDir dir;
  std::string path = dir.file("morph.animorph");
  REQUIRE(saveProject(doc->project(), path).ok());
  auto back = loadProject(path);
  INFO(back.error());
  REQUIRE(back.ok());
  CHECK(back->animorphosis == doc->project().animorphosis);

  // The project's generic tree, at the actors' clip times: C is A before t0 and B after t1.
  auto c = projectGenericTree(*back);
  INFO(c.error());
  REQUIRE(c.ok());
  AnimorphosisTiming t = animorphosisTiming(*back);
  CHECK(t.target.offsetSec == 0.5);
  BlobTree before = instantiateGeneric(*c, t, 0.5);
  CHECK(before.root.subtreeSize() == c->size());

  // A node deleted from a tree drops its links on save instead of making the file unreadable.
  exec(*doc, deleteBlobNodeCommand(doc->project(), "walker", 12));
  REQUIRE(saveProject(doc->project(), path).ok());
  auto pruned = loadProject(path);
  INFO(pruned.error());
  REQUIRE(pruned.ok());
  const auto& drawn = doc->project().animorphosis.graph.links;
  size_t untouched = size_t(std::count_if(drawn.begin(), drawn.end(), [](const auto& l) { return l.nodeA != 12; }));
  CHECK(untouched < drawn.size());
  CHECK(pruned->animorphosis.graph.links.size() == untouched);

  std::string text = projectToJson(*back);
  auto broken = [&](const std::string& from, const std::string& to) {
    std::string t2 = text;
    size_t at = t2.find(from);
    REQUIRE(at != std::string::npos);
    t2.replace(at, from.size(), to);
    auto r = projectFromJson(t2, "morph.animorph");
    REQUIRE_FALSE(r.ok());
    return r.error();
  };
  CHECK_THAT(broken("\"end\": 3.0", "\"end\": 0.5"), Contains("morph.animorph") && Contains("animorphosis.end"));
  CHECK_THAT(broken("\"target\": \"flyer\"", "\"target\": \"ghost\""), Contains("'ghost'"));
  CHECK_THAT(broken("\"b\": 105", "\"b\": 4242"), Contains("morph.animorph") && Contains("4242"));
}

TEST_CASE("animorphosis: the project's animorphosis bakes to a key-frame BlobTree actor", "[animorph]") {
  auto doc = creaturesDocument();
  exec(*doc, createAnimorphosisCommand(doc->project(), "walker", "flyer", 1.0, 3.0, true));
  auto c = projectGenericTree(doc->project());
  REQUIRE(c.ok());
  BakedAnimorphosis baked = bakeKeyframes(*c, animorphosisTiming(doc->project()));
  REQUIRE(validateBlobTree(baked.tree).ok());
  CHECK(baked.report.parameters > 50);
  CHECK(baked.report.keys > baked.report.parameters);
  Project p = doc->project();
  Actor morph = makeBlobTreeActor(p, "walker to flyer");
  morph.blobTree = baked.tree;
  p.actors.push_back(morph);
  auto back = projectFromJson(projectToJson(p), "baked.animorph");
  INFO(back.error());
  REQUIRE(back.ok());
  CHECK(back->findActor(morph.id)->blobTree == baked.tree);
}

TEST_CASE("animorphosis: Bake to key-frame actor adds one actor that evaluates to C at the key times, undo removes it",
          "[animorph]") {
  auto doc = creaturesDocument();
  Project noLoops = doc->project();  // a looping clip puts more than nA + nB + ns keys on a channel
  for (Actor& a : noLoops.actors) a.loop = false;
  doc->reset(noLoops, "");
  exec(*doc, createAnimorphosisCommand(doc->project(), "walker", "flyer", 1.0, 3.0, false));
  // The authored graph without the bridged tails: the baked tree then has C's node kinds at both ends.
  AnimorphosisSetup setup = doc->project().animorphosis;
  setup.graph = walkerToFlyerGraph();
  std::erase_if(setup.graph.links, [](const CorrespondenceLink& l) { return l.nodeA >= 9 && l.nodeA <= 11; });
  doc->execute(setAnimorphosisCommand(doc->project(), setup, "graph"));
  const size_t actorsBefore = doc->project().actors.size();

  auto baked = bakeAnimorphosisActor(doc->project());
  INFO(baked.error());
  REQUIRE(baked.ok());
  CHECK(baked->report.withinBound);
  CHECK(baked->report.mostKeys <= baked->report.mostKeysBound);
  CHECK(baked->report.keys > baked->report.parameters);
  const std::string text = describeBakedActor(*baked);
  CHECK_THAT(text, Contains("walker -> flyer (keys)"));
  CHECK_THAT(text, Contains("nA + nB + ns"));

  doc->execute(addBakedActorCommand(doc->project(), *baked));
  REQUIRE(doc->project().actors.size() == actorsBefore + 1);
  const Actor& added = doc->project().actors.back();
  CHECK(added.id == "walker_to_flyer");
  CHECK(added.kind == ActorKind::BlobTree);
  CHECK_FALSE(added.loop);
  REQUIRE(validateBlobTree(added.blobTree).ok());

  // At the interval's ends and at the global s's keys (keys of every channel) the actor's field is C's.
  auto c = projectGenericTree(doc->project());
  REQUIRE(c.ok());
  const AnimorphosisTiming timing = animorphosisTiming(doc->project());
  std::vector<double> keyTimes;
  for (const auto& k : timing.globalS.keys()) keyTimes.push_back(timing.startSec + k.timeSec * (timing.endSec - timing.startSec));
  REQUIRE(keyTimes.size() >= 2);
  FieldEvaluator ev;
  double worst = 0.0;
  for (double t : keyTimes) {
    const double clipT = (t - added.timeOffsetSec) * added.speed;
    FieldProgram pb = compileFieldProgram(added.blobTree, clipT), live = compileGeneric(*c, timing, t);
    for (int i = 0; i < 200; ++i) {
      const glm::vec3 p(-2.0f + 0.02f * float(i), 0.3f * std::sin(float(i)), -1.0f + 0.01f * float(i));
      const double fb = ev.evaluatePoint(pb, p), fl = ev.evaluatePoint(live, p);
      worst = std::max(worst, std::abs(fb - fl) / std::max(std::abs(fl), double(live.threshold)));
    }
  }
  CHECK(worst <= 1e-4);

  // A second bake gets its own id; undo removes the actors again.
  doc->execute(addBakedActorCommand(doc->project(), *baked));
  CHECK(doc->project().findActor("walker_to_flyer_2"));
  doc->undo();
  doc->undo();
  CHECK(doc->project().actors.size() == actorsBefore);
  CHECK_FALSE(doc->project().findActor("walker_to_flyer"));

  // Without an animorphosis nothing is baked, and the reason says so.
  Project none = doc->project();
  none.animorphosis = {};
  CHECK_FALSE(bakeAnimorphosisActor(none).ok());
}

TEST_CASE("animorphosis: a key-frame bake cancelled after some nodes stops there and leaves the document unchanged",
          "[animorph]") {
  auto demo = makeAnimorphosisDemoProject();
  INFO(demo.error());
  REQUIRE(demo.ok());
  Document doc;
  doc.reset(*demo, "");
  const uint64_t revision = doc.revision();
  const size_t actors = doc.project().actors.size();
  auto c = projectGenericTree(doc.project());
  REQUIRE(c.ok());
  REQUIRE(c->size() >= 7000);

  // The cancel flag turns on once 40 nodes are baked; the bake must not report (bake) another.
  constexpr size_t kStopAfter = 40;
  std::atomic<bool> cancel{false};
  size_t calls = 0, lastDone = 0, total = 0;
  BakeKeysSettings settings;
  settings.cancel = &cancel;
  settings.progress = [&](size_t done, size_t all) {
    ++calls;
    CHECK(done > lastDone);  // per node, forward
    lastDone = done;
    total = all;
    if (done == kStopAfter) cancel.store(true);
  };
  auto baked = bakeAnimorphosisActor(doc.project(), settings);
  REQUIRE_FALSE(baked.ok());
  CHECK(isJobCancelled(Status(Error{baked.error()})));
  CHECK(calls == kStopAfter);
  CHECK(lastDone == kStopAfter);
  CHECK(total == c->size());
  CHECK(doc.revision() == revision);
  CHECK(doc.project().actors.size() == actors);
  CHECK_FALSE(doc.dirty());

  // The core bake says it was cancelled and hands back nothing half-made.
  cancel.store(true);
  BakedAnimorphosis none = bakeKeyframes(*c, animorphosisTiming(doc.project()), settings);
  CHECK(none.cancelled);
  CHECK(none.report.parameters == 0);
  CHECK(none.tree.root.children.empty());
}
