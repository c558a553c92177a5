#include <catch2/catch.hpp>

#include "core/io/gltf_export.h"
#include "core/rig/vertex_colors.h"
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
  // The vertex's textured colour (the scales texture x COLOR_0) before A, fading into the
  // stand-in's through the collapse (tests/core/morph_colors.cpp holds the fade's values).
  const StandinBinding& b = (*rt)->source.binding;
  REQUIRE(b.hasColors());
  const std::vector<glm::vec4> textured = characterVertexColors(creature);
  REQUIRE(textured.size() == total);
  CHECK(b.vertexColors[13] == textured[13]);
  for (int frame : {mk.a - 2, (mk.a + mk.b) / 2}) {  // skinned source, collapse
    auto fr = evaluateMorphFrame(**rt, frame / fps, s);
    REQUIRE(fr.ok());
    REQUIRE(fr->mesh.positions.size() >= total);  // the collapse: then the stand-in core's vertices
    REQUIRE(fr->mesh.colors.size() == fr->mesh.positions.size());
    if (frame < mk.a) CHECK(fr->mesh.colors[13] == textured[13]);
    std::vector<float> alpha;
    transitionAlphas(fr->progress, (*rt)->setup.easing, (*rt)->source.morph.weightMap, (*rt)->setup.weightMapShift, false, total,
                     alpha);
    CHECK(glm::distance(fr->mesh.colors[13], glm::mix(b.vertexColors[13], b.standinColors[13], alpha[13])) < 1e-6f);
  }
  // The implicit morph and the gear carry colours too (the stand-ins' and the gear's bronze).
  for (int frame : {(mk.b + mk.c) / 2, mk.d + 2}) {
    auto fr = evaluateMorphFrame(**rt, frame / fps, s);
    REQUIRE(fr.ok());
    CHECK(fr->mesh.colors.size() == fr->mesh.positions.size());
  }
}
