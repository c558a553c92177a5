#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <random>

#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "util/blob_builders.h"
#include "util/temp_dir.h"

using namespace animorph;
using namespace animorph::test;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

json scene(json root) {
  return json{{"format", "animorph-blobtree"}, {"version", 1}, {"threshold", 0.5}, {"root", root}};
}

json blendOf(json children) { return json{{"id", 1}, {"type", "blend"}, {"children", children}}; }

std::string parseError(const json& j) {
  auto r = blobTreeFromJson(j, "creature.json");
  REQUIRE_FALSE(r.ok());
  return r.error();
}

}  // namespace

TEST_CASE("BlobTree JSON round trip keeps every node, id and track", "[blobtree]") {
  for (unsigned seed = 1; seed <= 25; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.6f);
    tree.threshold.setKey(2.0, 0.7f);
    json j = blobTreeSceneToJson(tree);
    auto back = blobTreeFromJson(json::parse(j.dump()), "mem");
    REQUIRE(back.ok());
    // Quaternions are normalised on reading; after that the text is stable.
    json j2 = blobTreeSceneToJson(*back);
    auto again = blobTreeFromJson(json::parse(j2.dump()), "mem");
    REQUIRE(again.ok());
    CHECK(blobTreeSceneToJson(*again) == j2);
    CHECK(back->root.subtreeSize() == tree.root.subtreeSize());
    // Same field at a few times and points.
    for (double t : {0.0, 0.5, 1.5}) {
      FieldProgram a = compileFieldProgram(tree, t), b = compileFieldProgram(*back, t);
      FieldEvaluator ev;
      for (glm::vec3 x : {glm::vec3(0.1f, 0.2f, -0.1f), glm::vec3(-0.3f, 0, 0.2f), glm::vec3(0)})
        CHECK(ev.evaluatePoint(a, x) == Approx(ev.evaluatePoint(b, x)).margin(1e-6));
    }
  }
}

TEST_CASE("the embeddable form sits under a project's blobtree key", "[blobtree]") {
  BlobTree tree = treeOf(pointNode(5, {0, 0, 0}, 0.5f));
  json project = {{"format", "animorph"}, {"version", 1}, {"blobtree", blobTreeToJson(tree)}};
  auto r = parseBlobTreeScene(project.dump(), "demo.animorph");
  REQUIRE(r.ok());
  CHECK(r->root.id == 5);
  json noTree = {{"format", "animorph"}, {"version", 1}};
  CHECK_THAT(parseBlobTreeScene(noTree.dump(), "demo.animorph").error(), Contains("demo.animorph") && Contains("blobtree"));
}

TEST_CASE("bad scenes give errors that name the file and the node id", "[blobtree]") {
  json seg = {{"id", 7}, {"type", "convSegment"}, {"params", {{"a", {0, 0, 0}}, {"b", {1, 0, 0}}, {"radius", 0.1}}}};
  REQUIRE(blobTreeFromJson(scene(blendOf(json::array({seg}))), "x").ok());

  json unknown = seg;
  unknown["type"] = "blub";
  CHECK_THAT(parseError(scene(blendOf(json::array({unknown})))), Contains("creature.json") && Contains("node 7") && Contains("unknown node type 'blub'"));

  json missing = seg;
  missing["params"].erase("radius");
  CHECK_THAT(parseError(scene(blendOf(json::array({missing})))), Contains("node 7") && Contains("missing parameter 'radius'"));

  json nan = seg;
  nan["params"]["radius"] = std::nan("");
  CHECK_THAT(parseError(scene(blendOf(json::array({nan})))), Contains("node 7") && Contains("radius") && Contains("NaN"));

  json nanKey = seg;
  nanKey["params"]["a"] = {{"keys", {{{"t", 0}, {"v", {0, std::nan(""), 0}}}}}};
  CHECK_THAT(parseError(scene(blendOf(json::array({nanKey})))), Contains("node 7") && Contains("'a'"));

  json negative = seg;
  negative["params"]["radius"] = {{"keys", {{{"t", 0}, {"v", 0.1}}, {{"t", 1}, {"v", -0.2}}}}};
  CHECK_THAT(parseError(scene(blendOf(json::array({negative})))), Contains("node 7") && Contains("negative") && Contains("key 1"));

  json hyper = {{"id", 9}, {"type", "hyperBlend"}, {"params", {{"q", 0.5}}}, {"children", {seg}}};
  CHECK_THAT(parseError(scene(hyper)), Contains("node 9") && Contains("'q'") && Contains(">= 1"));

  json unknownParam = seg;
  unknownParam["params"]["radiu"] = 0.1;
  CHECK_THAT(parseError(scene(blendOf(json::array({unknownParam})))), Contains("node 7") && Contains("unknown parameter 'radiu'"));

  json dup = seg;
  dup["id"] = 1;
  CHECK_THAT(parseError(scene(blendOf(json::array({dup})))), Contains("id 1") && Contains("another node"));

  json bb = {{"id", 4}, {"type", "boundedBlend"}, {"children", {seg}}};
  CHECK_THAT(parseError(scene(bb)), Contains("node 4") && Contains("children"));

  json noId = {{"type", "point"}};
  CHECK_THAT(parseError(scene(blendOf(json::array({noId})))), Contains("id"));

  json newer = scene(blendOf(json::array({seg})));
  newer["version"] = 99;
  CHECK_THAT(parseError(newer), Contains("version 99"));

  json badThreshold = scene(blendOf(json::array({seg})));
  badThreshold["threshold"] = -1;
  CHECK_THAT(parseError(badThreshold), Contains("threshold"));

  CHECK_THAT(parseBlobTreeScene("{not json", "broken.json").error(), Contains("broken.json") && Contains("JSON"));
}

TEST_CASE("validation of trees built in code", "[blobtree]") {
  BlobTree tree = treeOf(operatorNode(NodeType::Blend, 1, {pointNode(2, {0, 0, 0}, 0.5f)}));
  CHECK(validateBlobTree(tree).ok());
  tree.root.children[0].floatParam("radius") = FloatTrack(std::nanf(""));
  CHECK_THAT(validateBlobTree(tree).error(), Contains("node 2") && Contains("NaN"));
  tree.root.children[0].floatParam("radius") = FloatTrack(-1.0f);
  CHECK_THAT(validateBlobTree(tree).error(), Contains("node 2") && Contains("negative"));
  tree.root.children[0].floatParam("radius") = FloatTrack(0.5f);
  BlobNode frame = makeBlobNode(NodeType::Frame, 3);
  frame.children.push_back(pointNode(4, {0, 0, 0}, 0.3f));
  frame.vec3Param("scale") = Vec3Track(glm::vec3(1, 0, 1));
  tree.root.children.push_back(frame);
  CHECK_THAT(validateBlobTree(tree).error(), Contains("node 3") && Contains("scale"));
  CHECK(tree.nextId() == 5);
  CHECK(tree.find(4) != nullptr);
  CHECK(tree.find(42) == nullptr);
}

TEST_CASE("scene files: save, load, and errors naming the file", "[blobtree]") {
  TempDir dir;
  std::mt19937 rng(3);
  int id = 1;
  BlobTree tree = treeOf(randomNode(rng, 3, id));
  REQUIRE(saveBlobTreeScene(tree, dir.file("scene.json")).ok());
  auto back = loadBlobTreeScene(dir.file("scene.json"));
  REQUIRE(back.ok());
  CHECK(back->root.subtreeSize() == tree.root.subtreeSize());
  CHECK_THAT(loadBlobTreeScene(dir.file("missing.json")).error(), Contains("missing.json"));
}

TEST_CASE("meta-primitives expand when flattened, animation changes the field", "[blobtree]") {
  BlobNode tail = makeBlobNode(NodeType::SplineOfNodes, 1);
  ControlPoints pts;
  pts.push_back(Vec3Track(glm::vec3(0, 0, 0)));
  pts.push_back(Vec3Track(glm::vec3(0.5f, 0, 0)));
  Vec3Track moving(glm::vec3(1, 0, 0));
  moving.setKey(1.0, glm::vec3(1, 0.5f, 0));
  pts.push_back(moving);
  tail.pointsParam("points") = pts;
  tail.floatParam("count") = FloatTrack(6.0f);
  tail.children.push_back(pointNode(2, {0, 0, 0}, 0.2f));
  BlobTree tree = treeOf(tail);
  REQUIRE(validateBlobTree(tree).ok());
  FieldProgram p0 = compileFieldProgram(tree, 0.0), p1 = compileFieldProgram(tree, 1.0);
  CHECK(p0.primitiveCount() == 6);
  CHECK(p0.maps.size() == 6);
  FieldEvaluator ev;
  CHECK(ev.evaluatePoint(p0, {1, 0, 0}) > 0.0f);    // a copy sits at the last point
  CHECK(ev.evaluatePoint(p1, {1, 0, 0}) < 0.0f);    // which moved up by t = 1
  CHECK(ev.evaluatePoint(p1, {1, 0.5f, 0}) > 0.0f);
}
