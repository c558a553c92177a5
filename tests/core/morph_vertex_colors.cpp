#include <catch2/catch.hpp>

#include "core/io/gltf_export.h"
#include "core/scene/morph_runtime.h"
#include "util/morph_fixtures.h"
#include "util/temp_dir.h"

using namespace animorph;

TEST_CASE("morph frames carry the characters' vertex colours on the skinned and transition stages", "[morph][export]") {
  const test::DemoMorph& demo = test::demoMorph();
  // The demo with a creature whose vertices are coloured by index.
  Character creature = test::demoCreature();
  size_t total = 0;
  for (Mesh& m : creature.meshes) {
    m.colors.resize(m.vertexCount());
    for (size_t i = 0; i < m.colors.size(); ++i) m.colors[i] = {float(i % 7) / 6.0f, 0.25f, 0.5f, 1.0f};
    total += m.vertexCount();
  }
  test::TempDir dir;
  REQUIRE(exportGlb(creature, dir.file("creature.glb")).ok());
  REQUIRE(exportGlb(test::demoGear(), dir.file("gear.glb")).ok());
  AssetCache assets;
  auto rt = prepareMorph(demo.project, dir.path().string(), assets);
  REQUIRE(rt.ok());
  const MorphMarkers& mk = demo.project.morph.markers;
  const double fps = demo.project.timeline.fps;
  MorphFrameSettings s;
  s.resolution = 24;
  for (int frame : {mk.a - 2, (mk.a + mk.b) / 2}) {  // skinned source, collapse
    auto fr = evaluateMorphFrame(**rt, frame / fps, s);
    REQUIRE(fr.ok());
    REQUIRE(fr->mesh.positions.size() >= total);  // the collapse: then the stand-in core's vertices
    REQUIRE(fr->mesh.colors.size() == fr->mesh.positions.size());
    CHECK(fr->mesh.colors[13] == glm::vec4(float(13 % 7) / 6.0f, 0.25f, 0.5f, 1.0f));
  }
  // The gear has no colours; the implicit morph has none of its own.
  for (int frame : {(mk.b + mk.c) / 2, mk.d + 2}) {
    auto fr = evaluateMorphFrame(**rt, frame / fps, s);
    REQUIRE(fr.ok());
    CHECK(fr->mesh.colors.empty());
  }
}
