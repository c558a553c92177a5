// A morph whose source or target is a BlobTree actor (its own tree plays the
// stand-in's role, no transition on that side): the skinned creature -> the
// blob creature and the blob creature -> the gear bake with every frame
// watertight and manifold, the first frames with the source's topology and the
// last with the target's; markers A = B (C = D) on the BlobTree side.
#include <catch2/catch.hpp>

#include "core/blobtree/compile.h"
#include "demo/blob_creature.h"
#include "core/doc/morph_create.h"
#include "core/doc/document.h"
#include "core/project/project_io.h"
#include "core/scene/morph_runtime.h"
#include "core/poly/mesh_checks.h"
#include "core/scene/morph_scene.h"
#include "util/mesh_checks.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

// The demo morph with the blob creature in place of its source or target.
Project withBlobSide(bool blobIsTarget) {
  Project p = test::demoMorph().project;
  Actor a;
  a.id = "blobc";
  a.name = "blob creature";
  a.kind = ActorKind::BlobTree;
  a.blobTree = makeBlobCreature();
  p.actors.push_back(a);
  (blobIsTarget ? p.morph.targetActorId : p.morph.sourceActorId) = "blobc";
  return p;
}

std::shared_ptr<const MorphRuntime> prepared(const Project& p) {
  AssetCache assets;
  auto rt = prepareMorph(p, test::demoMorph().dir, assets);
  INFO((rt ? std::string() : rt.error()));
  REQUIRE(rt.ok());
  return *rt;
}

// The blob creature polygonised by itself (no morph) at scene time t.
TriangleMesh blobAlone(const MorphRuntime& rt, const MorphActorRuntime& a, double t, int res) {
  const MorphOperand op = posedOperand(a, t, -1.0);
  FieldProgram p;
  appendMorphOperand(p, op, 1.0f);
  p.finish();
  PolygonizeSettings ps;
  ps.resolution = res;
  auto r = polygonize(p, ps);
  REQUIRE(r.ok());
  (void)rt;
  return r->mesh;
}

struct Shape {
  long genus = 0;
  size_t components = 0;
  size_t vertices = 0;
};

Shape shapeOf(const TriangleMesh& m) {
  const test::Topology t = test::weldedTopology(m.positions, m.indices);
  return {t.genus(), t.components, m.positions.size()};
}

// The frame's mesh has the topology (and vertex count) of side's tree polygonised alone.
void checkTreeAlone(const MorphRuntime& rt, const MorphActorRuntime& side, const MorphFrame& fr) {
  const Shape alone = shapeOf(blobAlone(rt, side, fr.timeSec, 24));
  const Shape got = shapeOf(fr.mesh);
  CHECK(got.genus == alone.genus);
  CHECK(got.components == alone.components);
  CHECK(got.vertices == alone.vertices);
}

// Every frame of the timeline at res: closed and manifold (welded: the skinned
// meshes repeat positions at UV seams), never empty.
std::vector<MorphFrame> bakeAll(const MorphRuntime& rt, int res) {
  MorphFrameSettings fs;
  fs.resolution = res;
  std::vector<MorphFrame> out;
  for (int f = rt.timeline.frameStart; f <= rt.timeline.frameEnd; ++f) {
    auto fr = evaluateMorphFrame(rt, rt.timeline.frameToSec(f), fs);
    REQUIRE(fr.ok());
    INFO("frame " << f << " (" << morphStageName(fr->stage) << ")");
    CHECK(fr->mesh.triangleCount() > 50);
    const test::Topology t = test::weldedTopology(fr->mesh.positions, fr->mesh.indices);
    CHECK(t.boundaryOrNonManifoldEdges == 0);
    CHECK(t.inconsistentEdges == 0);
    if (fr->stage == MorphStage::Morph || (fr->actorId == "blobc")) {
      const MeshTopology topo = analyzeMesh(fr->mesh);
      CHECK(topo.manifold());
      CHECK(topo.degenerateTriangles == 0);
    }
    out.push_back(std::move(*fr));
  }
  return out;
}

}  // namespace

TEST_CASE("morph with a BlobTree target: the project used to fail, now prepares with C = D", "[morph][blobtree]") {
  const Project p = withBlobSide(true);
  const auto rt = prepared(p);
  CHECK(rt->target.isTree());
  CHECK_FALSE(rt->source.isTree());
  CHECK(rt->setup.markers.d == rt->setup.markers.c);
  CHECK(rt->setup.markers.a == p.morph.markers.a);
  double u = 0.0;
  CHECK(morphStageAt(rt->setup, rt->timeline, rt->timeline.frameToSec(p.morph.markers.c + 1), u) ==
        MorphStage::Target);
  // Saved and loaded, the project keeps its BlobTree side and still prepares.
  auto back = projectFromJson(projectToJson(p), "blob_side.animorph");
  REQUIRE(back.ok());
  CHECK(back->morph.targetActorId == "blobc");
  prepared(*back);
}

TEST_CASE("morph with a BlobTree side: a threshold other than the stand-ins' is refused by name", "[morph][blobtree]") {
  Project p = withBlobSide(true);
  p.findActor("blobc")->blobTree.threshold = FloatTrack(0.5f);
  AssetCache assets;
  auto rt = prepareMorph(p, test::demoMorph().dir, assets);
  REQUIRE_FALSE(rt.ok());
  CHECK_THAT(rt.error(), Catch::Contains("morph.target: actor 'blobc'") && Catch::Contains("threshold"));
}

TEST_CASE("morph: skinned creature -> BlobTree creature, every frame closed and manifold", "[morph][blobtree]") {
  const auto rt = prepared(withBlobSide(true));
  const std::vector<MorphFrame> frames = bakeAll(*rt, 24);
  const MorphMarkers& k = rt->setup.markers;
  const Shape creature = shapeOf(frames.front().mesh);
  CHECK(frames.front().stage == MorphStage::Source);
  CHECK(creature.vertices == test::demoCreature().totalVertices());
  CHECK(creature.genus == 0);
  for (int f = 0; f < k.a; ++f) CHECK(shapeOf(frames[size_t(f)].mesh).vertices == creature.vertices);
  // From C on: the blob creature itself, as it polygonises alone.
  for (int f : {k.c, k.c + 1, rt->timeline.frameEnd}) {
    const MorphFrame& fr = frames[size_t(f)];
    INFO("frame " << f);
    checkTreeAlone(*rt, rt->target, fr);
    if (f > k.c) CHECK(fr.actorId == "blobc");
  }
}

TEST_CASE("morph: BlobTree creature -> gear, every frame closed and manifold", "[morph][blobtree]") {
  const auto rt = prepared(withBlobSide(false));
  CHECK(rt->setup.markers.a == rt->setup.markers.b);
  const std::vector<MorphFrame> frames = bakeAll(*rt, 24);
  const MorphMarkers& k = rt->setup.markers;
  for (int f : {0, k.b - 1, k.b}) {
    const MorphFrame& fr = frames[size_t(f)];
    INFO("frame " << f);
    checkTreeAlone(*rt, rt->source, fr);
  }
  CHECK(frames[size_t(k.b - 1)].stage == MorphStage::Source);
  CHECK(frames[size_t(k.b - 1)].actorId == "blobc");
  for (int f : {k.d + 1, rt->timeline.frameEnd}) {
    const MorphFrame& fr = frames[size_t(f)];
    CHECK(fr.actorId == "gear");
    CHECK(shapeOf(fr.mesh).genus == 5);
    CHECK(fr.mesh.positions.size() == test::demoGear().totalVertices());
  }
}

TEST_CASE("morph scene with a BlobTree side: its own draw shows until the morph, then the morph replaces it",
          "[morph][blobtree]") {
  const Project p = withBlobSide(false);
  const auto rt = prepared(p);
  AssetCache assets;
  MorphFrameSettings s;
  s.resolution = 16;
  auto blobsAt = [&](int f) {
    SceneFrame frame = evaluateScene(p, test::demoMorph().dir, assets, p.timeline.frameToSec(f));
    const MorphSceneInfo info = applyMorph(frame, rt, p.timeline.frameToSec(f), s);
    REQUIRE(info.error.empty());
    size_t n = 0;
    for (const BlobDraw& b : frame.blobs) n += b.actorId == "blobc";
    return n;
  };
  CHECK(blobsAt(p.morph.markers.b - 2) == 1);
  CHECK(blobsAt((p.morph.markers.b + p.morph.markers.c) / 2) == 0);
  CHECK(blobsAt(p.timeline.frameEnd) == 0);
}

TEST_CASE("Create > Morph's setup: any two actors, a stand-in fitted for a glTF side, one undo step, swap",
          "[morph][blobtree]") {
  Project p = withBlobSide(true);
  p.morph = MorphSetup{};  // no morph yet
  AssetCache assets;
  MorphChoice c;
  c.sourceActorId = "gear";
  c.targetActorId = "blobc";
  c.markers = {10, 20, 40, 50};
  std::vector<std::string> notes;
  auto m = proposeMorph(p, test::demoMorph().dir, assets, c, &notes);
  REQUIRE(m.ok());
  CHECK(m->markers == MorphMarkers{10, 20, 40, 40});  // C = D on the BlobTree target
  REQUIRE(m->findActor("gear"));
  CHECK(m->findActor("gear")->standin.segments.size() > 2);  // fitted
  CHECK(m->findActor("blobc") == nullptr);
  CHECK(notes.size() == 1);
  const std::string path = test::demoMorph().dir + "/create_morph.animorph";
  REQUIRE(saveProject(p, path).ok());
  auto opened = Document::open(path);
  REQUIRE(opened.ok());
  Document& doc = **opened;
  doc.execute(setMorphCommand(doc.project(), *m, "Create morph"));
  CHECK(doc.project().morph.sourceActorId == "gear");
  doc.execute(swapMorphSidesCommand(doc.project()));
  CHECK(doc.project().morph.sourceActorId == "blobc");
  CHECK(doc.project().morph.targetActorId == "gear");
  // Mirrored in [A, D]: no collapse (the BlobTree had no expansion), the gear expands over 10 frames.
  CHECK(doc.project().morph.markers == MorphMarkers{10, 10, 30, 40});
  REQUIRE(doc.undo());
  CHECK(doc.project().morph.sourceActorId == "gear");
  REQUIRE(doc.undo());
  CHECK_FALSE(doc.project().morph.enabled());
  // Refusals name the problem.
  c.targetActorId = "gear";
  auto same = proposeMorph(p, test::demoMorph().dir, assets, c);
  REQUIRE_FALSE(same.ok());
  CHECK_THAT(same.error(), Catch::Contains("same actor"));
  c.targetActorId = "nobody";
  auto missing = proposeMorph(p, test::demoMorph().dir, assets, c);
  REQUIRE_FALSE(missing.ok());
  CHECK_THAT(missing.error(), Catch::Contains("morph.target: no actor with id 'nobody'"));
}
