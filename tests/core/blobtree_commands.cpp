#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>

#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "demo/blob_creature.h"
#include "core/doc/actor_commands.h"
#include "core/doc/blobtree_commands.h"
#include "core/doc/document.h"
#include "util/blob_builders.h"

using namespace animorph;

namespace {

// A document with one BlobTree actor "blob" holding the starter tree (blend of one sphere).
std::unique_ptr<Document> blobDocument() {
  auto d = std::make_unique<Document>();
  Project p;
  p.actors.push_back(makeBlobTreeActor(p, "blob"));
  d->reset(p, "");
  return d;
}

const BlobTree& treeOf(const Document& d) { return d.project().findActor("blob")->blobTree; }

void exec(Document& d, Result<std::unique_ptr<Command>> c) {
  INFO(c.error());
  REQUIRE(c.ok());
  d.execute(std::move(*c));
}

ParamAddress param(const BlobTree& t, int node, const char* name, int point = -1) {
  return {node, paramIndex(t.find(node)->type, name), point};
}

float radiusAt(const BlobTree& t, int node, double timeSec) {
  return t.find(node)->floatParam("radius").evaluate(timeSec);
}

}  // namespace

TEST_CASE("a new BlobTree actor is a valid blend of one visible sphere", "[blobtree][commands]") {
  Project p;
  Actor a = makeBlobTreeActor(p, "My Blob");
  CHECK(a.kind == ActorKind::BlobTree);
  CHECK(a.id == "my_blob");
  CHECK(a.blobTree.root.type == NodeType::Blend);
  REQUIRE(a.blobTree.root.children.size() == 1);
  CHECK(a.blobTree.root.children[0].type == NodeType::Sphere);
  CHECK(validateBlobTree(a.blobTree).ok());
  // The field is positive at the sphere's centre: there is a surface to see.
  FieldProgram prog = compileFieldProgram(a.blobTree, 0.0);
  FieldEvaluator ev;
  CHECK(ev.evaluatePoint(prog, glm::vec3(0.0f)) > 0.0f);
  CHECK(ev.evaluatePoint(prog, glm::vec3(2.0f, 0.0f, 0.0f)) < 0.0f);
}

TEST_CASE("new BlobTree actors get names no other actor has, as outliners number them", "[blobtree][commands]") {
  Project p;
  for (const char* expected : {"Blob", "Blob 2", "Blob 3"}) {
    Actor a = makeBlobTreeActor(p, "Blob");
    CHECK(a.name == expected);
    p.actors.push_back(std::move(a));
  }
  CHECK(p.uniqueActorName("Blob 2") == "Blob 4");  // counts on from the number a name ends with
  CHECK(p.uniqueActorName("Statue") == "Statue");
  p.actors[1].name = "Gone";  // a freed name is taken again
  CHECK(p.uniqueActorName("Blob") == "Blob 2");
  CHECK(p.uniqueActorName("Blob 2") == "Blob 2");
  // Ids stay what they were: unique, and independent of the display name.
  CHECK(p.actors[0].id != p.actors[1].id);
  CHECK(p.actors[1].id != p.actors[2].id);
  // The same glTF file imported twice.
  Actor w1 = actorForAsset(p, "/assets/walker.glb", "/assets");
  p.actors.push_back(w1);
  Actor w2 = actorForAsset(p, "/assets/walker.glb", "/assets");
  CHECK(w1.name == "walker");
  CHECK(w2.name == "walker 2");
  CHECK(w2.id != w1.id);
}

TEST_CASE("every node type can be added, keeps the tree valid and is undoable", "[blobtree][commands]") {
  auto d = blobDocument();
  int root = treeOf(*d).root.id;
  for (const NodeTypeInfo& info : allNodeTypes()) {
    INFO(info.name);
    int id = -1;
    exec(*d, addBlobNodeCommand(d->project(), "blob", root, info.type, &id));
    const BlobNode* n = treeOf(*d).find(id);
    REQUIRE(n);
    CHECK(n->type == info.type);
    CHECK(int(n->children.size()) >= info.minChildren);
    CHECK(validateBlobTree(treeOf(*d)).ok());
  }
  CHECK(treeOf(*d).root.children.size() == 1 + allNodeTypes().size());
  // The whole thing polygonises to a non-empty field.
  FieldProgram prog = compileFieldProgram(treeOf(*d), 0.0);
  CHECK(prog.primitiveCount() > allNodeTypes().size());
  size_t steps = d->history().size();
  for (size_t i = 0; i < steps; ++i) REQUIRE(d->undo());
  CHECK(treeOf(*d) == makeStarterTree());
  CHECK(d->history().undoLabel().empty());
}

TEST_CASE("adding under a primitive or a full operator is refused with a message", "[blobtree][commands]") {
  auto d = blobDocument();
  int sphere = treeOf(*d).root.children[0].id;
  auto r = addBlobNodeCommand(d->project(), "blob", sphere, NodeType::Point);
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.error(), Catch::Contains("takes at most 0 children"));
  CHECK_THAT(r.error(), Catch::Contains("actor 'blob'"));
  CHECK_FALSE(addBlobNodeCommand(d->project(), "nobody", 1, NodeType::Point).ok());
  CHECK(d->history().size() == 0);
}

TEST_CASE("delete removes a subtree, refuses the root and minimum arities, undo restores", "[blobtree][commands]") {
  auto d = blobDocument();
  int root = treeOf(*d).root.id;
  int diff = -1;
  exec(*d, addBlobNodeCommand(d->project(), "blob", root, NodeType::Difference, &diff));
  REQUIRE(treeOf(*d).find(diff)->children.size() == 2);
  int child = treeOf(*d).find(diff)->children[0].id;
  auto refused = deleteBlobNodeCommand(d->project(), "blob", child);
  REQUIRE_FALSE(refused.ok());
  CHECK_THAT(refused.error(), Catch::Contains("needs at least 2 children"));
  CHECK_THAT(refused.error(), Catch::Contains("node " + std::to_string(diff)));
  CHECK_FALSE(deleteBlobNodeCommand(d->project(), "blob", root).ok());

  BlobTree before = treeOf(*d);
  exec(*d, deleteBlobNodeCommand(d->project(), "blob", diff));
  CHECK(treeOf(*d).find(diff) == nullptr);
  CHECK(treeOf(*d).find(child) == nullptr);
  CHECK(d->undo());
  CHECK(treeOf(*d) == before);
  CHECK(d->redo());
  CHECK(treeOf(*d).find(diff) == nullptr);
}

TEST_CASE("duplicate copies a subtree with fresh ids right after the original", "[blobtree][commands]") {
  auto d = blobDocument();
  int root = treeOf(*d).root.id;
  int frame = -1;
  exec(*d, addBlobNodeCommand(d->project(), "blob", root, NodeType::Frame, &frame));
  int copy = -1;
  exec(*d, duplicateBlobNodeCommand(d->project(), "blob", frame, &copy));
  const BlobTree& t = treeOf(*d);
  REQUIRE(t.find(copy));
  CHECK(copy != frame);
  CHECK(t.root.children.size() == 3);
  CHECK(t.root.children[1].id == frame);
  CHECK(t.root.children[2].id == copy);
  // Same shape, all ids distinct.
  CHECK(t.find(copy)->subtreeSize() == t.find(frame)->subtreeSize());
  CHECK(t.find(copy)->children[0].id != t.find(frame)->children[0].id);
  CHECK(t.find(copy)->params == t.find(frame)->params);
  CHECK(validateBlobTree(t).ok());  // unique ids are part of validation
  CHECK_FALSE(duplicateBlobNodeCommand(d->project(), "blob", root).ok());
  d->undo();
  CHECK(treeOf(*d).find(copy) == nullptr);
}

TEST_CASE("reparent moves nodes, refuses cycles and arity violations", "[blobtree][commands]") {
  auto d = blobDocument();
  int root = treeOf(*d).root.id;
  int sphere = treeOf(*d).root.children[0].id;
  int frame = -1, bounded = -1, inner = -1;
  exec(*d, addBlobNodeCommand(d->project(), "blob", root, NodeType::Frame, &frame));
  exec(*d, addBlobNodeCommand(d->project(), "blob", frame, NodeType::Blend, &inner));
  exec(*d, addBlobNodeCommand(d->project(), "blob", root, NodeType::BoundedBlend, &bounded));

  // Into its own subtree: a cycle.
  auto cycle = reparentBlobNodeCommand(d->project(), "blob", frame, inner);
  REQUIRE_FALSE(cycle.ok());
  CHECK_THAT(cycle.error(), Catch::Contains("cycle"));
  CHECK_FALSE(reparentBlobNodeCommand(d->project(), "blob", frame, frame).ok());
  // Into a full operator (bounded blend takes exactly 3).
  auto full = reparentBlobNodeCommand(d->project(), "blob", sphere, bounded);
  REQUIRE_FALSE(full.ok());
  CHECK_THAT(full.error(), Catch::Contains("at most 3"));
  // Out of an operator that would fall below its minimum.
  int boundedChild = treeOf(*d).find(bounded)->children[0].id;
  auto underflow = reparentBlobNodeCommand(d->project(), "blob", boundedChild, root);
  REQUIRE_FALSE(underflow.ok());
  CHECK_THAT(underflow.error(), Catch::Contains("at least 3"));
  CHECK_FALSE(reparentBlobNodeCommand(d->project(), "blob", root, frame).ok());

  // A valid move, then undo.
  BlobTree before = treeOf(*d);
  exec(*d, reparentBlobNodeCommand(d->project(), "blob", sphere, inner));
  CHECK(treeOf(*d).find(inner)->children.back().id == sphere);
  CHECK(validateBlobTree(treeOf(*d)).ok());
  d->undo();
  CHECK(treeOf(*d) == before);
  // Onto a later sibling of the node (the erase shifts it in memory).
  exec(*d, reparentBlobNodeCommand(d->project(), "blob", sphere, frame));
  CHECK(treeOf(*d).root.children.size() == 2);
  CHECK(treeOf(*d).find(frame)->children.back().id == sphere);
  CHECK(treeOf(*d).find(frame)->subtreeSize() == before.find(frame)->subtreeSize() + 1);
  CHECK(validateBlobTree(treeOf(*d)).ok());
}

TEST_CASE("rename is undoable and refuses empty names", "[blobtree][commands]") {
  auto d = blobDocument();
  int sphere = treeOf(*d).root.children[0].id;
  exec(*d, renameBlobNodeCommand(d->project(), "blob", sphere, "head"));
  CHECK(treeOf(*d).find(sphere)->name == "head");
  CHECK(d->history().undoLabel() == "Rename sphere to head");
  CHECK_FALSE(renameBlobNodeCommand(d->project(), "blob", sphere, "").ok());
  d->undo();
  CHECK(treeOf(*d).find(sphere)->name == "sphere");
}

TEST_CASE("setting a parameter: constants change, the key button animates, animated values key", "[blobtree][commands]") {
  auto d = blobDocument();
  int s = treeOf(*d).root.children[0].id;
  ParamAddress radius = param(treeOf(*d), s, "radius");

  // A constant parameter just changes, at any time.
  exec(*d, setBlobParamCommand(d->project(), "blob", radius, 0.5, 0.6f, false));
  CHECK(keyCount(treeOf(*d), radius) == 1);
  CHECK(radiusAt(treeOf(*d), s, 0.0) == 0.6f);
  CHECK(radiusAt(treeOf(*d), s, 3.0) == 0.6f);

  // Key button at t = 0, then at t = 1 with a new value: now animated.
  exec(*d, setBlobParamCommand(d->project(), "blob", radius, 0.0, 0.6f, true));
  CHECK(keyCount(treeOf(*d), radius) == 1);
  exec(*d, setBlobParamCommand(d->project(), "blob", radius, 1.0, 0.6f, true));
  CHECK(keyCount(treeOf(*d), radius) == 2);
  exec(*d, setBlobParamCommand(d->project(), "blob", radius, 1.0, 1.0f, false));  // edit at the key: replaces it
  CHECK(keyCount(treeOf(*d), radius) == 2);
  CHECK(radiusAt(treeOf(*d), s, 0.0) == 0.6f);
  CHECK(radiusAt(treeOf(*d), s, 1.0) == 1.0f);
  float mid = radiusAt(treeOf(*d), s, 0.5);
  CHECK(mid > 0.6f);
  CHECK(mid < 1.0f);
  // Editing an animated parameter between keys creates a key there.
  exec(*d, setBlobParamCommand(d->project(), "blob", radius, 0.5, 0.3f, false));
  CHECK(keyCount(treeOf(*d), radius) == 3);
  CHECK(radiusAt(treeOf(*d), s, 0.5) == Approx(0.3f));

  // Values are clamped to the parameter's rule; NaN and wrong kinds are refused.
  exec(*d, setBlobParamCommand(d->project(), "blob", radius, 0.5, -2.0f, false));
  CHECK(radiusAt(treeOf(*d), s, 0.5) == 0.0f);
  CHECK_FALSE(setBlobParamCommand(d->project(), "blob", radius, 0.5, std::nanf(""), false).ok());
  CHECK_FALSE(setBlobParamCommand(d->project(), "blob", radius, 0.5, glm::vec3(1.0f), false).ok());
  CHECK(validateBlobTree(treeOf(*d)).ok());

  // Every step undoes back to the starter tree.
  while (d->undo()) {
  }
  CHECK(treeOf(*d) == makeStarterTree());
}

TEST_CASE("vector, rotation and control-point parameters take keys", "[blobtree][commands]") {
  auto d = blobDocument();
  int root = treeOf(*d).root.id;
  int frame = -1, curve = -1;
  exec(*d, addBlobNodeCommand(d->project(), "blob", root, NodeType::Frame, &frame));
  exec(*d, addBlobNodeCommand(d->project(), "blob", root, NodeType::Curve, &curve));
  ParamAddress rot = param(treeOf(*d), frame, "rotation");
  glm::quat q = glm::angleAxis(1.0f, glm::vec3(0, 1, 0));
  exec(*d, setBlobParamCommand(d->project(), "blob", rot, 0.0, glm::quat(1, 0, 0, 0), true));
  exec(*d, setBlobParamCommand(d->project(), "blob", rot, 2.0, q, true));
  glm::quat half = treeOf(*d).find(frame)->quatParam("rotation").evaluate(1.0);
  CHECK(glm::angle(half) == Approx(0.5f).margin(1e-4));
  // A rotation channel reads as Euler degrees.
  ParamSample v;
  REQUIRE(sampleParam(treeOf(*d), rot, 2.0, v));
  CHECK(channelOf(v, 1) == Approx(glm::degrees(1.0f)).margin(1e-3));

  ParamAddress p1 = param(treeOf(*d), curve, "points", 1);
  exec(*d, setBlobParamCommand(d->project(), "blob", p1, 0.0, glm::vec3(0, 0.2f, 0), true));
  exec(*d, setBlobParamCommand(d->project(), "blob", p1, 1.0, glm::vec3(0, 0.6f, 0), true));
  CHECK(isAnimated(treeOf(*d), p1));
  CHECK_FALSE(isAnimated(treeOf(*d), param(treeOf(*d), curve, "points", 0)));
  CHECK(animatedKeyTimes(treeOf(*d), curve) == std::vector<double>{0.0, 1.0});
  CHECK(animatedKeyTimes(treeOf(*d), frame) == std::vector<double>{0.0, 2.0});
  CHECK(animationEndSec(treeOf(*d)) == 2.0);
  // A zero scale is refused (a frame scale must be non-zero).
  CHECK_FALSE(setBlobParamCommand(d->project(), "blob", param(treeOf(*d), frame, "scale"), 0.0, glm::vec3(1, 0, 1),
                                  false).ok());
}

TEST_CASE("keys: delete, move (merged while dragging), interpolation and tangents", "[blobtree][commands]") {
  auto d = blobDocument();
  int s = treeOf(*d).root.children[0].id;
  ParamAddress radius = param(treeOf(*d), s, "radius");
  for (auto [t, v] : {std::pair{0.0, 0.4f}, {1.0, 0.8f}, {2.0, 0.4f}})
    exec(*d, setBlobParamCommand(d->project(), "blob", radius, t, v, true));
  REQUIRE(keyCount(treeOf(*d), radius) == 3);
  size_t base = d->history().size();

  SECTION("a drag of several steps is one undo step; the selection follows the key") {
    BlobTree original = treeOf(*d);
    std::vector<KeyChannelRef> sel = {{{radius, 1}, 0}};
    d->beginDrag();
    std::vector<KeyChannelRef> moved;
    for (int step = 1; step <= 5; ++step)
      exec(*d, moveBlobKeysCommand(d->project(), "blob", original, sel, 0.25 * step, 0.02f * step, "drag", &moved));
    d->endDrag();
    CHECK(d->history().size() == base + 1);
    // The middle key moved past the last one: it is now last, and the selection says so.
    REQUIRE(moved.size() == 1);
    CHECK(moved[0].key.key == 2);
    double t = 0.0;
    ParamSample v;
    REQUIRE(keyAt(treeOf(*d), moved[0].key, t, v));
    CHECK(t == Approx(2.25));
    CHECK(std::get<float>(v) == Approx(0.9f));
    d->undo();
    CHECK(treeOf(*d) == original);
  }
  SECTION("a key moved onto another replaces it") {
    BlobTree original = treeOf(*d);
    exec(*d, moveBlobKeysCommand(d->project(), "blob", original, {{{radius, 0}, 0}}, 1.0, 0.0f));
    CHECK(keyCount(treeOf(*d), radius) == 2);
    CHECK(radiusAt(treeOf(*d), s, 1.0) == 0.4f);
  }
  SECTION("delete keys; deleting every key leaves a constant") {
    exec(*d, deleteBlobKeysCommand(d->project(), "blob", {{radius, 1}}));
    CHECK(keyCount(treeOf(*d), radius) == 2);
    CHECK(radiusAt(treeOf(*d), s, 1.0) == Approx(0.4f));
    exec(*d, deleteBlobKeysCommand(d->project(), "blob", {{radius, 0}, {radius, 1}}));
    CHECK(keyCount(treeOf(*d), radius) == 1);
    CHECK(radiusAt(treeOf(*d), s, 5.0) == Approx(0.4f));
    CHECK(validateBlobTree(treeOf(*d)).ok());
    d->undo();
    d->undo();
    CHECK(keyCount(treeOf(*d), radius) == 3);
  }
  SECTION("constant and linear interpolation") {
    exec(*d, setBlobKeyInterpCommand(d->project(), "blob", {{radius, 0}}, KeyInterp::Constant));
    CHECK(radiusAt(treeOf(*d), s, 0.9) == Approx(0.4f));
    exec(*d, setBlobKeyInterpCommand(d->project(), "blob", {{radius, 0}}, KeyInterp::Linear));
    CHECK(radiusAt(treeOf(*d), s, 0.5) == Approx(0.6f));
    d->undo();
    d->undo();
    CHECK(radiusAt(treeOf(*d), s, 0.5) != Approx(0.6f));  // Hermite again
  }
  SECTION("user tangents keep the curve, then set the slope") {
    BlobTree before = treeOf(*d);
    std::vector<float> samples;
    for (int i = 0; i <= 20; ++i) samples.push_back(radiusAt(before, s, i * 0.1));
    exec(*d, setBlobKeyTangentModeCommand(d->project(), "blob", {{radius, 0}, {radius, 1}, {radius, 2}}, true));
    for (int i = 0; i <= 20; ++i) CHECK(radiusAt(treeOf(*d), s, i * 0.1) == Approx(samples[size_t(i)]).margin(1e-6));
    // Slope 0 at the middle key: a flat top, the curve stays at or below 0.8 around it.
    exec(*d, setBlobKeyTangentCommand(d->project(), "blob", treeOf(*d), {{radius, 1}, 0}, 0.0f));
    CHECK(keySlope(treeOf(*d), {{radius, 1}, 0}) == 0.0f);
    CHECK(radiusAt(treeOf(*d), s, 0.95) <= 0.8f);
    CHECK(radiusAt(treeOf(*d), s, 1.05) <= 0.8f);
    // A steep slope overshoots.
    exec(*d, setBlobKeyTangentCommand(d->project(), "blob", treeOf(*d), {{radius, 1}, 0}, 3.0f));
    CHECK(radiusAt(treeOf(*d), s, 1.1) > 0.8f);
    CHECK_FALSE(setBlobKeyTangentCommand(d->project(), "blob", treeOf(*d), {{radius, 9}, 0}, 1.0f).ok());
  }
}

TEST_CASE("the demo creature survives a round of edits and undo exactly", "[blobtree][commands]") {
  auto d = std::make_unique<Document>();
  Project p;
  Actor a = makeBlobTreeActor(p, "blob");
  a.blobTree = makeBlobCreature();
  p.actors.push_back(a);
  d->reset(p, "");
  const BlobTree original = treeOf(*d);
  std::vector<int> ids;
  std::function<void(const BlobNode&)> collect = [&](const BlobNode& n) {
    ids.push_back(n.id);
    for (const auto& c : n.children) collect(c);
  };
  collect(original.root);
  int done = 0;
  // Leaves first, so a deleted subtree does not take the later ids with it.
  for (auto it = ids.rbegin(); it != ids.rend(); ++it) {
    int id = *it;
    if (id == original.root.id) continue;
    if (auto c = duplicateBlobNodeCommand(d->project(), "blob", id); c) {
      d->execute(std::move(*c));
      ++done;
    }
    if (auto c = deleteBlobNodeCommand(d->project(), "blob", id); c) {
      d->execute(std::move(*c));
      ++done;
    }
    REQUIRE(validateBlobTree(treeOf(*d)).ok());
  }
  CHECK(done > 10);
  while (d->undo()) {
  }
  CHECK(treeOf(*d) == original);
}

TEST_CASE("animationEndSec is the last of the tree's animated key times", "[blobtree]") {
  int animated = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    std::mt19937 rng(seed);
    int next = 1;
    BlobTree tree = test::treeOf(test::randomNode(rng, 4, next));
    const std::vector<double> times = animatedKeyTimes(tree, -1);
    INFO("seed " << seed << ", " << times.size() << " key times");
    animated += !times.empty();
    if (times.empty()) CHECK(animationEndSec(tree) == 0.0);
    else CHECK(animationEndSec(tree) == Approx(times.back()).margin(kSameKeyTimeSec));
  }
  CHECK(animated >= 10);
  BlobTree still = test::treeOf(test::pointNode(1, {0, 0, 0}, 0.5f));
  CHECK(animationEndSec(still) == 0.0);
  still.threshold = FloatTrack(0.5f);
  still.threshold.setKey(0.0, 0.4f);
  still.threshold.setKey(3.5, 0.6f);
  CHECK(animationEndSec(still) == 3.5);  // the threshold's keys count too
}
