#include <catch2/catch.hpp>

#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "demo/blob_creature.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"

using namespace animorph;

TEST_CASE("the demo creature is one closed animated body", "[demo]") {
  BlobTree tree = makeBlobCreature();
  REQUIRE(validateBlobTree(tree).ok());
  double previousVolume = 0.0;
  for (double t : {0.0, 0.5, 1.0}) {
    FieldProgram p = compileFieldProgram(tree, t);
    PolygonizeSettings s;
    s.resolution = 64;
    auto r = polygonize(p, s);
    REQUIRE(r.ok());
    MeshTopology topo = analyzeMesh(r->mesh);
    INFO("t = " << t);
    CHECK(topo.manifold());
    CHECK(topo.components == 1);  // legs, head and tail all join the body
    double v = meshVolume(r->mesh);
    CHECK(v > 0.0);
    if (t == 1.0) CHECK(v > previousVolume);  // the torso breathes in towards t = 1
    previousVolume = v;
  }
}

TEST_CASE("the committed demo scene is what make-blob-demo writes", "[demo]") {
  auto onDisk = loadBlobTreeScene(std::string(ANIMORPH_SOURCE_DIR) + "/resources/demo/blob_creature.json");
  REQUIRE(onDisk.ok());
  CHECK(blobTreeSceneToJson(*onDisk) == blobTreeSceneToJson(makeBlobCreature()));
}
