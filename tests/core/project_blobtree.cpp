#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/blobtree/blob_tree_json.h"
#include "demo/blob_creature.h"
#include "core/doc/blobtree_commands.h"
#include "core/project/project_io.h"
#include "core/scene/blob_guides.h"
#include "core/scene/scene_frame.h"

using namespace animorph;

namespace {
Project blobProject() {
  Project p;
  Actor g;
  g.id = "walker";
  g.name = "Walker";
  g.assetPath = "walker.glb";
  p.actors.push_back(g);
  Actor b = makeBlobTreeActor(p, "Creature");
  b.blobTree = makeBlobCreature();
  b.transform.translation = {1.0f, 0.0f, 0.0f};
  p.actors.push_back(b);
  return p;
}
}  // namespace

TEST_CASE("a project with a BlobTree actor round-trips through JSON", "[io][project][blobtree]") {
  Project p = blobProject();
  std::string text = projectToJson(p);
  auto back = projectFromJson(text, "blob.animorph");
  INFO(back.error());
  REQUIRE(back.ok());
  CHECK(*back == p);
  CHECK(back->actors[1].kind == ActorKind::BlobTree);
  CHECK(back->actors[0].kind == ActorKind::Gltf);
  // The form on disk: kind + the embeddable BlobTree form; glTF actors have no "kind".
  auto j = nlohmann::json::parse(text);
  CHECK_FALSE(j["actors"][0].contains("kind"));
  CHECK(j["actors"][1]["kind"] == "blobtree");
  CHECK(j["actors"][1]["blobtree"] == blobTreeToJson(makeBlobCreature()));
  CHECK_FALSE(j["actors"][1].contains("asset"));
}

TEST_CASE("BlobTree actor errors name the file, the actor and the node", "[io][project][blobtree]") {
  auto j = nlohmann::json::parse(projectToJson(blobProject()));
  SECTION("a bad parameter") {
    j["actors"][1]["blobtree"]["root"]["children"][0]["params"]["radius"] = -1.0;
    auto r = projectFromJson(j.dump(), "blob.animorph");
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error(), Catch::StartsWith("blob.animorph: actor 'creature': node "));
    CHECK_THAT(r.error(), Catch::Contains("radius"));
  }
  SECTION("a missing tree") {
    j["actors"][1].erase("blobtree");
    auto r = projectFromJson(j.dump(), "blob.animorph");
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error(), Catch::Contains("actors[1].blobtree: missing"));
  }
  SECTION("an unknown kind") {
    j["actors"][1]["kind"] = "voxels";
    auto r = projectFromJson(j.dump(), "blob.animorph");
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error(), Catch::Contains("unknown actor kind 'voxels'"));
  }
  SECTION("a glTF actor still needs its asset") {
    j["actors"][0].erase("asset");
    CHECK_FALSE(projectFromJson(j.dump(), "blob.animorph").ok());
  }
}

TEST_CASE("scene evaluation lists BlobTree actors with their guides and looped time", "[scene][blobtree]") {
  Project p = blobProject();
  p.actors[0].visible = false;  // no glTF to load in this test
  AssetCache cache;
  const Actor& blob = p.actors[1];
  double end = animationEndSec(blob.blobTree);
  REQUIRE(end == Approx(kBlobCreatureLoopSec));
  SceneFrame f = evaluateScene(p, ".", cache, end + 0.25);
  CHECK(f.errors.empty());
  REQUIRE(f.blobs.size() == 1);
  CHECK(f.blobs[0].actorId == "creature");
  CHECK(f.blobs[0].treeTimeSec == Approx(0.25));  // loops
  CHECK(f.blobs[0].model[3][0] == 1.0f);
  REQUIRE(f.blobGuides.get().size() == 1);
  const BlobGuides& g = f.blobGuides.get()[0];
  CHECK(g.actorId == "creature");
  CHECK(g.lines.size() > 10);
  CHECK(g.axes.size() >= 5);  // body, legs, head frames
  // Every guide is placed by the actor transform: x is shifted by 1 on average.
  Bounds b;
  for (const auto& l : g.lines) b.add(l.a);
  CHECK(b.center().x > 0.5f);
  // Without looping, time holds past the end.
  p.actors[1].loop = false;
  CHECK(blobActorTimeSec(p.actors[1], end + 0.25) == Approx(end + 0.25));
}

TEST_CASE("a node's parameter space follows its frames", "[scene][blobtree]") {
  BlobTree t = makeStarterTree();
  int next = t.nextId();
  BlobNode frame = makeDefaultNode(NodeType::Frame, next);
  frame.vec3Param("translation") = Vec3Track(glm::vec3(0.0f, 2.0f, 0.0f));
  frame.quatParam("rotation") = QuatTrack(glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1)));
  frame.vec3Param("scale") = Vec3Track(glm::vec3(2.0f));
  int child = frame.children[0].id;
  REQUIRE(addNode(t, t.root.id, frame).ok());
  NodeSpace s;
  glm::mat4 actor = glm::translate(glm::mat4(1.0f), glm::vec3(10.0f, 0.0f, 0.0f));
  REQUIRE(nodeSpace(t, child, 0.0, actor, s));
  // Local +X: scaled by 2, turned to +Y, lifted by 2, then moved by the actor.
  glm::vec3 w = s.toWorld(glm::vec3(1.0f, 0.0f, 0.0f));
  CHECK(w.x == Approx(10.0f).margin(1e-4));
  CHECK(w.y == Approx(4.0f).margin(1e-4));
  glm::mat3 J = s.jacobian(glm::vec3(0.0f));
  CHECK(J[0].y == Approx(2.0f).margin(1e-3));
  CHECK_FALSE(nodeSpace(t, 999, 0.0, actor, s));
}
