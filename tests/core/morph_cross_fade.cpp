// The cross-fade option of a morph (MorphSetup::crossFade): saved and loaded
// (older files without it load with it off), bad values named, and the scene
// around markers B and C holds the transitioned mesh and the implicit surface
// with complementary opacity; the GPU transition draws replace the CPU mesh.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "core/project/project_io.h"
#include "core/scene/transition_frame.h"
#include "core/scene/morph_scene.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

// The morph's draws in a scene evaluated at frame f (the source and target only).
struct MorphDraws {
  std::vector<MeshDraw> meshes;
  std::vector<TransitionDraw> transitions;
};

MorphDraws drawsAt(const std::shared_ptr<const MorphRuntime>& rt, const Project& p, const std::string& dir, double f,
                   bool gpu) {
  AssetCache assets;
  SceneFrame frame = evaluateScene(p, dir, assets, p.timeline.frameToSec(f));
  MorphFrameSettings s;
  s.resolution = 24;
  s.gpuTransitions = gpu;
  const MorphSceneInfo info = applyMorph(frame, rt, p.timeline.frameToSec(f), s);
  REQUIRE(info.error.empty());
  return {frame.meshes, frame.transitions};
}

}  // namespace

TEST_CASE("morph cross-fade: saved, older files load with it off, bad values named", "[morph][project]") {
  Project p = test::demoMorph().project;
  CHECK_FALSE(p.morph.crossFade.enabled);
  p.morph.crossFade = {true, 5};
  const std::string text = projectToJson(p);
  auto back = projectFromJson(text, "p.animorph");
  REQUIRE(back.ok());
  CHECK(back->morph.crossFade == MorphCrossFade{true, 5});
  CHECK(*back == p);

  nlohmann::json j = nlohmann::json::parse(text);
  j["morph"].erase("cross_fade");
  auto old = projectFromJson(j.dump(), "old.animorph");
  REQUIRE(old.ok());
  CHECK_FALSE(old->morph.crossFade.enabled);

  j["morph"]["cross_fade"] = {{"enabled", true}, {"width_frames", 0}};
  auto bad = projectFromJson(j.dump(), "p.animorph");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error() == "p.animorph: morph.cross_fade.width_frames: must be in 1..1000");
  j["morph"]["cross_fade"] = {{"enabled", "yes"}};
  bad = projectFromJson(j.dump(), "p.animorph");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error() == "p.animorph: morph.cross_fade.enabled: expected true or false");
}

TEST_CASE("morph cross-fade: around B and C both shapes are drawn with complementary opacity", "[morph]") {
  const test::DemoMorph& demo = test::demoMorph();
  Project p = demo.project;
  const MorphMarkers mk = p.morph.markers;
  AssetCache assets;

  // Off: the collapsing mesh and its stand-in core (scene/standin_core.h), both opaque.
  auto rtOff = prepareMorph(p, demo.dir, assets);
  REQUIRE(rtOff.ok());
  MorphDraws off = drawsAt(*rtOff, p, demo.dir, mk.b - 1, false);
  REQUIRE(off.meshes.size() == 2);
  CHECK(off.meshes[0].opacity == 1.0f);
  CHECK(off.meshes[1].opacity == 1.0f);

  p.morph.crossFade = {true, 4};
  auto rt = prepareMorph(p, demo.dir, assets);
  REQUIRE(rt.ok());
  // B - 1: the collapsing mesh at 5/8 over the stand-in core (opaque: it is the implicit
  // surface the transition fades towards, and already the whole stand-in at B).
  MorphDraws before = drawsAt(*rt, p, demo.dir, mk.b - 1, false);
  REQUIRE(before.meshes.size() == 2);
  CHECK(before.meshes[0].opacity == Approx(0.625f));
  CHECK_FALSE(before.meshes[0].complementDither);
  CHECK(before.meshes[1].opacity == 1.0f);
  CHECK_FALSE(before.meshes[1].complementDither);
  // B + 1 on the GPU: the collapsed mesh (a transition draw at alpha 1) at 3/8, the morph at 5/8.
  MorphDraws after = drawsAt(*rt, p, demo.dir, mk.b + 1, true);
  REQUIRE(after.meshes.size() == 1);
  REQUIRE_FALSE(after.transitions.empty());
  CHECK(after.meshes[0].opacity == Approx(0.625f));
  CHECK(after.transitions[0].mesh.opacity == Approx(0.375f));
  CHECK(after.transitions[0].frame->uniformAlpha == 1.0f);
  CHECK_FALSE(after.transitions[0].targetActor);
  // C + 2: the expanding target at 3/4 and its stand-in core.
  MorphDraws nearC = drawsAt(*rt, p, demo.dir, mk.c + 2, true);
  REQUIRE(nearC.meshes.size() == 1);
  REQUIRE_FALSE(nearC.transitions.empty());
  CHECK(nearC.transitions[0].targetActor);
  CHECK(nearC.meshes[0].opacity == 1.0f);
  CHECK(nearC.transitions[0].mesh.opacity == Approx(0.75f));
  // Outside the windows: one shape, opaque.
  MorphDraws mid = drawsAt(*rt, p, demo.dir, (mk.b + mk.c) / 2, true);
  CHECK(mid.meshes.size() == 1);
  CHECK(mid.transitions.empty());
}

TEST_CASE("morph scene: GPU transitions replace the CPU mesh, one draw per mesh node, bound in order", "[morph]") {
  const test::DemoMorph& demo = test::demoMorph();
  const Project& p = demo.project;
  const MorphMarkers mk = p.morph.markers;
  // Three quarters into the collapse: the core grows over its last half (kStandinCoreSpan).
  const int frame = mk.a + 3 * (mk.b - mk.a) / 4;
  MorphDraws gpu = drawsAt(demo.runtime, p, demo.dir, frame, true);
  CHECK(gpu.meshes.size() == 1);  // the stand-in core (a CPU mesh here: implicitStage)
  const Character& c = *demo.runtime->source.character;
  REQUIRE(gpu.transitions.size() == c.meshNodes().size());
  size_t first = 0;
  for (const TransitionDraw& t : gpu.transitions) {
    CHECK(t.firstVertex == first);
    CHECK(t.runtime == demo.runtime);
    first += c.meshes[size_t(t.mesh.meshIndex)].vertexCount();
    // The same progress the CPU uses: alpha strictly between 0 and 1.
    CHECK(t.frame->uniformAlpha > 0.0f);
    CHECK(t.frame->uniformAlpha < 1.0f);
  }
  CHECK(first == demo.runtime->source.vertexCount);
  MorphDraws cpu = drawsAt(demo.runtime, p, demo.dir, frame, false);
  CHECK(cpu.transitions.empty());
  CHECK(cpu.meshes.size() == 2);  // the collapsing mesh and the core
}
