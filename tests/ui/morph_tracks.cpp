// The morph's tracks in the curve editor and the rest of the morph's settings
// in the inspector: easing / blend presets, noise, projection, keyed stand-in
// segments (user-controlled morphing), driven through the real UI.
#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "core/doc/morph_tracks.h"
#include "core/scene/morph_runtime.h"
#include "core/standin_morph/transition.h"
#include "core/poly/mesh_checks.h"
#include "core/standin/fit_standin.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// The morph scene of EditorFixture (hero -> other, markers 10, 20, 30, 40: the
// morph runs over frames 20..30) with fitted stand-ins, in a tall window so the
// whole morph panel fits in the inspector.
struct MorphFixture {
  EditorFixture fixture{{1400.0f, 1300.0f}};
  TempDir& dir = fixture.dir;
  EditorHarness& h = fixture.h;

  MorphFixture() {
    fixture.loadHeroMorphScene();
    auto hero = h.assets.get(dir.file("hero.gltf")).character;
    REQUIRE(hero);
    auto fit = fitStandin(*hero);
    REQUIRE(fit);
    Project p = h.doc().project();
    for (const char* id : {"hero", "other"}) {
      ActorMorph am;
      am.actorId = id;
      am.standin = fit->standin;
      p.morph.actors.push_back(am);
    }
    h.document->reset(p, dir.file("scene.animorph"));
    h.frames(2);
  }
  const MorphSetup& morph() { return h.doc().project().morph; }
  // Ctrl+G with nothing selected: the curve editor on the morph's tracks.
  const CurveEditorState& openCurveEditor() {
    h.tapKey(GLFW_KEY_G, true);
    h.frames(3);
    return h.ui->state().curveEditor;
  }
};

std::shared_ptr<const MorphRuntime> prepare(EditorHarness& h, const Project& p) {
  auto rt = prepareMorph(p, h.doc().baseDir(), h.assets);
  REQUIRE(rt);
  return *rt;
}

}  // namespace

TEST_CASE("the curve editor shows the morph's tracks over u, an easing key drag is one undo step", "[morph][curves]") {
  MorphFixture f;
  auto& h = f.h;
  const CurveEditorState& ce = f.openCurveEditor();
  REQUIRE(ce.visible);
  CHECK(ce.sourceId == "morph");
  REQUIRE(h.hasWidget("curve/channel/Easing (transition u)"));
  REQUIRE(h.hasWidget("curve/channel/Blend w(u)"));
  REQUIRE(h.hasWidget("curve/channel/Noise amplitude"));
  // The view spans the normalised progress, not frames.
  CHECK(ce.frame0 < 0.0);
  CHECK(ce.frame1 > 1.0);
  CHECK(ce.frame1 < 2.0);
  // Blend and noise have keys on top of the easing's: hide them.
  h.clickWidget("curve/channel/Blend w(u)");
  h.clickWidget("curve/channel/Noise amplitude");
  const size_t steps = h.doc().history().size();
  // Drag the easing's key at u = 1 left by about 0.2 and down.
  glm::vec2 key = curveToPixel(ce, 1.0, 1.0);
  glm::vec2 perU = curveToPixel(ce, 1.0, 0.0) - curveToPixel(ce, 0.0, 0.0);
  h.drag(key, key + glm::vec2(-perU.x * 0.203f, 25.0f), 0, 8);
  CHECK(h.doc().history().size() == steps + 1);
  CHECK(h.doc().history().undoLabel() == "Move key");
  const FloatTrack& e = f.morph().easing;
  REQUIRE(e.keys().size() == 2);
  CHECK(e.keys()[1].timeSec == Approx(0.8).margin(1e-9));  // snapped to 0.01
  CHECK(e.keys()[1].value < 1.0f);
  CHECK(f.morph().blend == linearBlendTrack());  // hidden: untouched
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(f.morph().easing == smoothstepTrack());
  CHECK_FALSE(h.doc().dirty());
}

TEST_CASE("curve editor: double-click adds a blend key, Del removes it", "[morph][curves]") {
  MorphFixture f;
  auto& h = f.h;
  const CurveEditorState& ce = f.openCurveEditor();
  h.clickWidget("curve/channel/Easing (transition u)");
  h.clickWidget("curve/channel/Noise amplitude");
  glm::vec2 onCurve = curveToPixel(ce, 0.5, 0.5);
  h.settle();
  h.moveTo(onCurve);
  h.press();
  h.frames(1);
  h.release();
  h.frames(1);
  h.press();
  h.frames(1);
  h.release();
  h.frames(2);
  REQUIRE(f.morph().blend.keys().size() == 3);
  CHECK(f.morph().blend.keys()[1].timeSec == Approx(0.5));
  CHECK(f.morph().blend.keys()[1].value == Approx(0.5f));
  CHECK(ce.selection.size() == 1);
  h.tapKey(GLFW_KEY_DELETE);
  CHECK(f.morph().blend.keys().size() == 2);
  CHECK(h.doc().history().undoLabel() == "Delete key");
  // Ctrl+click on the curve adds one too (snapped to 0.01 of u).
  h.setModifiers(true);
  h.click(curveToPixel(ce, 0.252, 0.25));
  h.setModifiers(false);
  REQUIRE(f.morph().blend.keys().size() == 3);
  CHECK(f.morph().blend.keys()[1].timeSec == Approx(0.25));
  CHECK(h.doc().history().undoLabel() == "Add key");
}

TEST_CASE("easing and blend presets set the whole track in one command", "[morph]") {
  MorphFixture f;
  auto& h = f.h;
  REQUIRE(h.hasWidget("morph/easing/ease-in"));
  h.clickWidget("morph/easing/ease-in");
  CHECK(f.morph().easing.evaluate(0.5) == Approx(0.25f));
  CHECK(h.doc().history().size() == 1);
  h.clickWidget("morph/blend/ease-out");
  CHECK(f.morph().blend.evaluate(0.5) == Approx(0.75f));
  h.clickWidget("morph/easing/linear");
  CHECK(f.morph().easing.evaluate(0.3) == Approx(0.3f));
  CHECK(h.doc().history().size() == 3);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(f.morph().easing.evaluate(0.5) == Approx(0.25f));
  // The transition uses the easing: at half the collapse alpha is ease-in's 0.25.
  std::vector<float> alpha;
  transitionAlphas(0.5, f.morph().easing, {}, 0.0f, false, 3, alpha);
  CHECK(alpha[0] == Approx(0.25f));
}

TEST_CASE("a segment radius keyed at u = 0.5 changes the morph at that frame", "[morph][segments]") {
  MorphFixture f;
  auto& h = f.h;
  const Project plain = h.doc().project();
  h.doc().setCurrentFrame(25);  // u = 0.5 between B = 20 and C = 30
  h.frames(1);
  REQUIRE(h.hasWidget("morph/segment/source/0"));
  h.clickWidget("morph/segment/source/0");
  REQUIRE(h.hasWidget("morph/seg/radius/key"));
  h.clickWidget("morph/seg/radius/key");
  const ActorMorph* src = slotActor(f.morph(), MorphSlot::Source);
  REQUIRE(src->segmentTracks.size() == 1);
  CHECK(src->segmentTracks[0].segment == 0);
  // Drag the radius scale up (one step), keyed at u = 0.5.
  glm::vec2 c = h.widgetCenter("morph/seg/radius");
  h.drag(c, c + glm::vec2(80.0f, 0.0f), 0, 6);
  CHECK(h.doc().history().size() == 2);
  const SegmentTracks& t = slotActor(f.morph(), MorphSlot::Source)->segmentTracks[0];
  const float k = t.radiusScale.evaluate(0.5);
  CHECK(k > 1.2f);
  CHECK(t.radiusScale.evaluate(0.0) == Approx(1.0f));
  CHECK(t.radiusScale.evaluate(1.0) == Approx(1.0f));

  // The morph uses it: the posed operand's segment grows at this frame, and so does the surface.
  const double timeSec = 25.0 / h.doc().project().timeline.fps;
  auto keyed = prepare(h, h.doc().project());
  auto before = prepare(h, plain);
  const MorphOperand a = posedOperand(keyed->source, timeSec, 0.5);
  const MorphOperand b = posedOperand(before->source, timeSec, 0.5);
  CHECK(a.segments[0].radius == Approx(b.segments[0].radius * k));
  CHECK(a.segments[1].radius == Approx(b.segments[1].radius));
  MorphFrameSettings fs;
  fs.resolution = 32;
  auto fa = evaluateMorphFrame(*keyed, timeSec, fs);
  auto fb = evaluateMorphFrame(*before, timeSec, fs);
  REQUIRE(fa);
  REQUIRE(fb);
  REQUIRE(fa->stage == MorphStage::Morph);
  CHECK(meshVolume(fa->mesh) > meshVolume(fb->mesh) * 1.01);

  // Remove the tracks: one undo step, the segment follows its stand-in again.
  h.clickWidget("morph/seg/remove");
  CHECK(slotActor(f.morph(), MorphSlot::Source)->segmentTracks.empty());
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(slotActor(f.morph(), MorphSlot::Source)->segmentTracks.size() == 1);
}

TEST_CASE("the projection settings and report show in the morph panel", "[morph][projection]") {
  MorphFixture f;
  auto& h = f.h;
  h.ctx.morphRuntime = prepare(h, h.doc().project());
  h.clickWidget("morph/projection");
  h.frames(1);
  REQUIRE(h.hasWidget("morph/report/source"));
  REQUIRE(h.hasWidget("morph/projection/iterations"));
  glm::vec2 c = h.widgetCenter("morph/projection/iterations");
  h.drag(c, c + glm::vec2(-100.0f, 0.0f), 0, 6);
  CHECK(f.morph().projection.maxIterations < 40);
  CHECK(h.doc().history().size() == 1);
  h.clickWidget("morph/projection/pose");
  h.frames(1);
  // The pose combo's second entry: the clip at a time.
  glm::vec2 pose = h.widgetCenter("morph/projection/pose");
  h.click(pose + glm::vec2(0.0f, 2.0f * ImGui::GetFrameHeight()));
  CHECK(f.morph().projection.atClipTime);
  // A new projection re-binds the vertices (what the app's morph cache does on a new revision).
  auto rt = prepare(h, h.doc().project());
  CHECK(rt->setup.projection == f.morph().projection);
  CHECK(rt->source.binding.stats.points > 0);
}

TEST_CASE("everything edited in the morph panel and curve editor survives save and load", "[morph][file]") {
  MorphFixture f;
  auto& h = f.h;
  h.doc().setCurrentFrame(25);
  h.frames(1);
  h.clickWidget("morph/easing/ease-out");
  h.clickWidget("morph/noise/key");  // a noise key at u = 0.5
  glm::vec2 n = h.widgetCenter("morph/noise/amplitude");
  h.drag(n, n + glm::vec2(40.0f, 0.0f), 0, 4);
  glm::vec2 fq = h.widgetCenter("morph/noise/frequency");
  h.drag(fq, fq + glm::vec2(30.0f, 0.0f), 0, 4);
  REQUIRE(slotActor(f.morph(), MorphSlot::Target)->standin.segments.size() >= 2);
  REQUIRE(h.hasWidget("morph/segment/target/1"));
  h.clickWidget("morph/segment/target/1");
  // The x field of A offset (the first of the three).
  const auto ar = *h.ui->widgets().find("morph/seg/a_offset");
  glm::vec2 a{ar.min.x + 15.0f, ar.center().y};
  h.drag(a, a + glm::vec2(40.0f, 0.0f), 0, 4);
  h.clickWidget("morph/clips");
  h.frames(1);
  h.clickWidget("morph/target/loop");
  const MorphSetup& m = f.morph();
  CHECK(m.noiseAmplitude.keys().size() >= 2);
  CHECK(m.noiseAmplitude.evaluate(0.5) > 0.0f);
  CHECK(m.noiseFrequency > 8.0f);
  REQUIRE(slotActor(m, MorphSlot::Target)->segmentTracks.size() == 1);
  CHECK(slotActor(m, MorphSlot::Target)->segmentTracks[0].aOffset.evaluate(0.5).x != 0.0f);
  const bool loop = h.doc().project().findActor("other")->loop;

  const std::string path = f.dir.file("saved.animorph");
  REQUIRE(h.doc().saveAs(path));
  auto back = Document::open(path);
  REQUIRE(back);
  CHECK((*back)->project().morph == m);
  CHECK((*back)->project().findActor("other")->loop == loop);
}


namespace {
// The fixture's morph switched to skeleton correspondence and prepared: a copy of its automatic
// matching (the runtime is prepared again by the tests), the source's root chain and its name.
struct SkeletonMorph {
  SkeletonCorrespondence automatic;
  int root = -1;
  std::string name;
};
SkeletonMorph skeletonMorph(MorphFixture& f) {
  auto& h = f.h;
  Project p = h.doc().project();
  p.morph.method = MorphMethod::SkeletonCorrespondence;
  h.document->reset(p, f.dir.file("scene.animorph"));
  h.ctx.morphRuntime = prepare(h, h.doc().project());
  REQUIRE(h.ctx.morphRuntime->correspondence);
  const SkeletonCorrespondence& c = *h.ctx.morphRuntime->correspondence;
  const int root = c.source.mainRoot;
  REQUIRE(root >= 0);
  return {c, root, c.source.chains[size_t(root)].name};
}
}  // namespace

TEST_CASE("chain matching: a partner combo re-pairs a chain in one undo step, the preview and the file follow",
          "[morph][chain_pairs]") {
  MorphFixture f;
  auto& h = f.h;
  const auto [automatic, root, name] = skeletonMorph(f);
  REQUIRE(automatic.sourceMatch[size_t(root)] == automatic.target.mainRoot);  // the root rule
  h.frames(1);
  h.clickWidget("morph/chains");
  h.frames(1);
  const std::string combo = "morph/chains/source/" + std::to_string(root);
  REQUIRE(h.hasWidget(combo));
  CHECK_FALSE(h.hasWidget("morph/chains/reset/" + std::to_string(root)));  // automatic: nothing to reset
  // Hovering the row highlights the chain's stand-in segments in the viewport.
  CHECK(h.ui->output().highlightChain.lines.empty());
  h.moveTo(h.widgetCenter(combo));
  h.frames(1);
  CHECK(h.ui->output().highlightChain.lines.size() == automatic.source.chains[size_t(root)].segments.size());
  CHECK(h.ui->output().highlightChain.actorId == "hero");
  // Open the combo and pick "unmatched" (its second entry), overriding the root rule.
  h.clickWidget(combo);
  h.frames(1);
  REQUIRE(h.hasWidget("morph/chains/option/1"));
  h.clickWidget("morph/chains/option/1");
  CHECK(f.morph().chainPairs == std::vector<ChainPair>{{name, std::nullopt}});
  CHECK(h.doc().history().size() == 1);
  // The morph prepared again (as the app does on a new revision) follows the pair.
  h.ctx.morphRuntime = prepare(h, h.doc().project());
  const SkeletonCorrespondence& paired = *h.ctx.morphRuntime->correspondence;
  CHECK(paired.sourceMatch[size_t(root)] == -1);
  CHECK(paired.pinned[size_t(root)]);
  CHECK(paired.automatic[size_t(root)] == automatic.target.mainRoot);
  h.frames(2);
  // Saved and opened again, the pair is there.
  const std::string path = f.dir.file("paired.animorph");
  REQUIRE(h.doc().saveAs(path));
  auto back = Document::open(path);
  REQUIRE(back);
  CHECK((*back)->project().morph.chainPairs == f.morph().chainPairs);
  // The row's reset button gives the chain back to the automatic matching; undo restores the pair.
  REQUIRE(h.hasWidget("morph/chains/reset/" + std::to_string(root)));
  h.clickWidget("morph/chains/reset/" + std::to_string(root));
  CHECK(f.morph().chainPairs.empty());
  CHECK(h.doc().history().size() == 2);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(f.morph().chainPairs == std::vector<ChainPair>{{name, std::nullopt}});
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(f.morph().chainPairs.empty());
  // "Reset all to automatic" is disabled with no pair: clicking it changes nothing.
  h.frames(1);
  h.clickWidget("morph/chains/reset-all");
  CHECK_FALSE(h.doc().history().canUndo());
  CHECK(h.doc().history().canRedo());
}

TEST_CASE("the Correspondence Editor shows a skeleton-correspondence morph's chain matching and re-pairs its chains",
          "[morph][chain_pairs]") {
  MorphFixture f;
  auto& h = f.h;
  const auto [automatic, root, name] = skeletonMorph(f);
  h.frames(1);
  // View > Correspondence Editor: the project has no animorphosis, so the window is the chain matching.
  h.clickWidget("menu/View");
  h.frames(1);
  h.clickWidget("menu/Correspondence Editor");
  h.frames(2);
  REQUIRE(h.hasWidget("corr/window"));
  CHECK_FALSE(h.hasWidget("corr/tab/chains"));  // one thing to show: no tabs
  const std::string combo = "corr/chains/source/" + std::to_string(root);
  REQUIRE(h.hasWidget(combo));
  REQUIRE(h.hasWidget("corr/chains/target/0"));
  h.clickWidget(combo);
  h.frames(1);
  REQUIRE(h.hasWidget("corr/chains/option/1"));
  h.clickWidget("corr/chains/option/1");  // "unmatched"
  CHECK(f.morph().chainPairs == std::vector<ChainPair>{{name, std::nullopt}});
  CHECK(h.doc().history().size() == 1);
  h.ctx.morphRuntime = prepare(h, h.doc().project());
  h.frames(2);
  REQUIRE(h.hasWidget("corr/chains/reset/" + std::to_string(root)));
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(f.morph().chainPairs.empty());
}
