#include <catch2/catch.hpp>

#include <filesystem>
#include <random>

#include <nlohmann/json.hpp>

#include "core/util/base64.h"
#include "core/project/project_io.h"
#include "core/field/operators.h"
#include "core/standin_morph/mesh_distance.h"
#include "core/standin_morph/morph_field.h"
#include "core/scene/morph_runtime.h"
#include "core/poly/solid_noise.h"
#include "core/poly/mesh_checks.h"
#include "util/mesh_checks.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

MorphOperand operand(StandinKind kind, std::vector<PosedSegment> segs) {
  MorphOperand o;
  o.kind = kind;
  o.sharpness = 12.0f;
  o.segments = std::move(segs);
  return o;
}

std::vector<glm::vec3> samplePoints(int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> d(-0.6f, 1.6f);
  std::vector<glm::vec3> out;
  for (int i = 0; i < n; ++i) out.push_back({d(rng), d(rng) * 0.5f, d(rng) * 0.5f});
  return out;
}

long weldedGenus(const TriangleMesh& m) { return test::weldedTopology(m.positions, m.indices).genus(); }

}  // namespace

TEST_CASE("morph field: interpolation is (1 - w) f1 + w f2 and exact at the ends", "[morph]") {
  const MorphOperand a = operand(StandinKind::Convolution, {{{0, 0, 0}, {1, 0, 0}, 0.2f, 1.0f}});
  const MorphOperand b = operand(StandinKind::CapsuleUnion, {{{0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, 0.15f, 1.0f},
                                                             {{0.2f, 0.3f, 0}, {0.8f, 0.3f, 0}, 0.1f, 1.0f}});
  const FieldProgram f1 = standinProgram(a.kind, a.sharpness, a.segments);
  const FieldProgram f2 = standinProgram(b.kind, b.sharpness, b.segments);
  const FieldProgram m0 = buildMorphProgram(a, b, MorphMethod::Interpolation, 0.0f, {});
  const FieldProgram m1 = buildMorphProgram(a, b, MorphMethod::Interpolation, 1.0f, {});
  const FieldProgram mh = buildMorphProgram(a, b, MorphMethod::Interpolation, 0.3f, {});
  for (const auto& x : samplePoints(200)) {
    const float v1 = test::fieldAt(f1, x), v2 = test::fieldAt(f2, x);
    CHECK(test::fieldAt(m0, x) == v1);
    CHECK(test::fieldAt(m1, x) == v2);
    CHECK(test::fieldAt(mh, x) == Approx(0.7f * v1 + 0.3f * v2).margin(2e-3 * (1 + std::abs(v1) + std::abs(v2))));
  }
}

TEST_CASE("morph field: space-time blending follows paper 1, eq. 4", "[morph]") {
  const MorphOperand a = operand(StandinKind::Convolution, {{{0, 0, 0}, {1, 0, 0}, 0.2f, 1.0f}});
  const MorphOperand b = operand(StandinKind::Convolution, {{{0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, 0.15f, 1.0f}});
  const FieldProgram f1 = standinProgram(a.kind, a.sharpness, a.segments);
  const FieldProgram f2 = standinProgram(b.kind, b.sharpness, b.segments);
  SpaceTimeParams st;
  st.timeScale = 2.0f;
  st.a0 = 3.0f;
  st.a1 = 1.5f;
  st.a2 = 0.7f;
  st.a3 = 1.2f;
  const float w = 0.4f;
  const FieldProgram m = buildMorphProgram(a, b, MorphMethod::SpaceTime, w, st);
  const float tau = st.timeScale * w;
  for (const auto& x : samplePoints(200)) {
    float d1, d2, d[3];
    const float g1 = rIntersection(test::fieldAt(f1, x), -tau, d1, d2);
    const float g2 = rIntersection(test::fieldAt(f2, x), tau - st.timeScale, d1, d2);
    const float bound = rIntersection(tau, st.timeScale - tau, d1, d2);
    const float ref = boundedBlend(g1, g2, bound, {st.a0, st.a1, st.a2, st.a3}, d);
    CHECK(test::fieldAt(m, x) == Approx(ref).margin(1e-4));
  }
  // At w = 0 and 1 the morph is exactly the stand-in (the morph starts and ends on them).
  const auto x = samplePoints(1)[0];
  CHECK(test::fieldAt(buildMorphProgram(a, b, MorphMethod::SpaceTime, 0.0f, st), x) == test::fieldAt(f1, x));
  CHECK(test::fieldAt(buildMorphProgram(a, b, MorphMethod::SpaceTime, 1.0f, st), x) == test::fieldAt(f2, x));
}

TEST_CASE("morph project: JSON round trip, older files, bad values named", "[morph][project]") {
  Project p = test::demoMorph().project;
  MorphSetup& m = p.morph;
  m.method = MorphMethod::SpaceTime;
  m.spaceTime.a0 = 2.5f;
  m.actors[0].weightMap.assign(37, 0.25f);
  m.actors[0].weightMap[3] = 1.0f;
  SegmentTracks st;
  st.segment = 2;
  st.radiusScale.clearKeys();
  st.radiusScale.setKey(0.0, 1.0f);
  st.radiusScale.setKey(0.5, 0.2f);
  st.radiusScale.setKey(1.0, 1.0f);
  st.aOffset.setKey(0.5, glm::vec3(0.0f, 0.1f, 0.0f));
  m.actors[1].segmentTracks.push_back(st);
  m.noiseAmplitude.clearKeys();
  m.noiseAmplitude.setKey(0.0, 0.0f);
  m.noiseAmplitude.setKey(0.5, 0.01f);
  const std::string text = projectToJson(p);
  auto back = projectFromJson(text, "p.animorph");
  REQUIRE(back.ok());
  CHECK(*back == p);
  CHECK(projectToJson(*back) == text);

  // A project without a "morph" section still loads (format version 1).
  nlohmann::json j = nlohmann::json::parse(text);
  CHECK(j["version"] == 1);
  j.erase("morph");
  auto old = projectFromJson(j.dump(), "old.animorph");
  REQUIRE(old.ok());
  CHECK_FALSE(old->morph.enabled());

  // Deleting the target actor (as the editor may) keeps the file loadable.
  Project gone = p;
  std::erase_if(gone.actors, [&](const Actor& a) { return a.id == gone.morph.targetActorId; });
  auto reloaded = projectFromJson(projectToJson(gone), "gone.animorph");
  REQUIRE(reloaded.ok());
  CHECK_FALSE(reloaded->morph.enabled());

  auto expectError = [&](const std::function<void(nlohmann::json&)>& edit, const std::string& message) {
    nlohmann::json k = nlohmann::json::parse(text);
    edit(k);
    auto r = projectFromJson(k.dump(), "p.animorph");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error() == message);
  };
  expectError([](auto& k) { k["morph"]["markers"]["C"] = 10; }, "p.animorph: morph.markers.C: is before B");
  expectError([](auto& k) { k["morph"]["target"] = "nobody"; }, "p.animorph: morph.target: no actor with id 'nobody'");
  expectError([](auto& k) { k["morph"]["method"] = "magic"; },
              "p.animorph: morph.method: expected \"interpolation\", \"space_time\" or \"skeleton_correspondence\"");
  expectError([](auto& k) { k["morph"]["actors"][0]["weight_map"] = "abc"; },
              "p.animorph: morph.actors[0].weight_map: base64 length 3 is not a multiple of 4");
  expectError([](auto& k) { k["morph"]["actors"][0]["weight_map"] = floatsToBase64({0.5f, 2.0f}); },
              "p.animorph: morph.actors[0].weight_map[1]: must be in [0, 1]");
  expectError([](auto& k) { k["morph"]["actors"][1]["segment_tracks"][0]["segment"] = 99; },
              "p.animorph: morph.actors[1].segment_tracks[0].segment: no segment 99 in the stand-in (" +
                  std::to_string(p.morph.actors[1].standin.segments.size()) + " segments)");
  expectError([](auto& k) { k["morph"]["actors"][0]["standin"]["segments"][0]["radius"] = 0; },
              "p.animorph: morph.actors[0].standin.segments[0].radius: must be a positive number (metres)");
  expectError([](auto& k) { k["morph"]["space_time"]["a2"] = -1; },
              "p.animorph: morph.space_time: a1, a2 and a3 must be positive");
}

TEST_CASE("base64 float arrays round trip bit-exactly", "[morph][project]") {
  for (size_t n : {0u, 1u, 2u, 3u, 10u}) {
    std::vector<float> v;
    for (size_t i = 0; i < n; ++i) v.push_back(float(i) * 0.37f - 1.0f);
    auto back = floatsFromBase64(floatsToBase64(v), "w");
    REQUIRE(back.ok());
    CHECK(*back == v);
  }
  CHECK_FALSE(floatsFromBase64("AAA*", "w").ok());
}

TEST_CASE("morph stages follow the markers", "[morph]") {
  MorphSetup s;
  s.markers = {24, 48, 84, 108};
  Timeline tl;
  double u = 0.0;
  CHECK(morphStageAt(s, tl, 23 / 24.0, u) == MorphStage::Source);
  CHECK(morphStageAt(s, tl, 24 / 24.0, u) == MorphStage::Collapse);
  CHECK(u == Approx(0.0));
  CHECK(morphStageAt(s, tl, 36 / 24.0, u) == MorphStage::Collapse);
  CHECK(u == Approx(0.5));
  CHECK(morphStageAt(s, tl, 48 / 24.0, u) == MorphStage::Morph);
  CHECK(u == Approx(0.0));
  CHECK(morphStageAt(s, tl, 84 / 24.0, u) == MorphStage::Morph);
  CHECK(u == Approx(1.0));
  CHECK(morphStageAt(s, tl, 96 / 24.0, u) == MorphStage::Expand);
  CHECK(u == Approx(0.5));
  CHECK(morphStageAt(s, tl, 109 / 24.0, u) == MorphStage::Target);
}

TEST_CASE("morph: creature -> gear, every stage's mesh has the right topology", "[morph]") {
  const auto& rt = *test::demoMorph().runtime;
  const Timeline& tl = rt.timeline;
  const MorphMarkers& mk = rt.setup.markers;
  MorphFrameSettings fs;
  fs.resolution = 32;
  auto frameAt = [&](int f) {
    auto fr = evaluateMorphFrame(rt, tl.frameToSec(f), fs);
    REQUIRE(fr.ok());
    return std::move(*fr);
  };
  for (int f : {0, mk.a - 1}) {
    const MorphFrame fr = frameAt(f);
    CHECK(fr.stage == MorphStage::Source);
    CHECK(fr.actorId == "creature");
    CHECK(weldedGenus(fr.mesh) == 0);
  }
  for (int f : {mk.d + 1, tl.frameEnd}) {
    const MorphFrame fr = frameAt(f);
    CHECK(fr.stage == MorphStage::Target);
    CHECK(fr.actorId == "gear");
    CHECK(weldedGenus(fr.mesh) == 5);
  }
  // The core grows over the last half of the collapse and melts over the first half of the
  // expansion (kStandinCoreSpan): three quarters into the collapse, a quarter into the expansion.
  for (int f : {mk.a + 3 * (mk.b - mk.a) / 4, mk.c + (mk.d - mk.c) / 4}) {
    const MorphFrame fr = frameAt(f);
    CHECK((fr.stage == MorphStage::Collapse || fr.stage == MorphStage::Expand));
    // The character's mesh, then its stand-in core (scene/standin_core.h) as a second shell.
    const Character& c = fr.stage == MorphStage::Collapse ? test::demoCreature() : test::demoGear();
    CHECK(fr.coreTriangles > 0);
    CHECK(fr.mesh.triangleCount() - fr.coreTriangles == c.totalTriangles());
    CHECK(fr.mesh.positions.size() > c.totalVertices());
  }
  for (int k = 0; k <= 4; ++k) {
    const int f = mk.b + (mk.c - mk.b) * k / 4;
    const MorphFrame fr = frameAt(f);
    INFO("frame " << f << " (u = " << fr.progress << ")");
    CHECK(fr.stage == MorphStage::Morph);
    CHECK(fr.mesh.triangleCount() > 100);
    const MeshTopology topo = analyzeMesh(fr.mesh);
    CHECK(topo.watertight());
    CHECK(topo.manifold());
    CHECK(topo.degenerateTriangles == 0);
    CHECK(meshVolume(fr.mesh) > 0.0);
  }
}

namespace {

std::vector<MorphFrame> spaceTimeFrames() {
  Project p = test::demoMorph().project;
  p.morph.method = MorphMethod::SpaceTime;
  AssetCache assets;
  auto rt = prepareMorph(p, test::demoMorph().dir, assets);
  REQUIRE(rt.ok());
  MorphFrameSettings fs;
  fs.resolution = 24;
  std::vector<MorphFrame> out;
  for (int k = 1; k <= 7; ++k) {
    const int f = p.morph.markers.b + (p.morph.markers.c - p.morph.markers.b) * k / 8;
    auto fr = evaluateMorphFrame(**rt, p.timeline.frameToSec(f), fs);
    REQUIRE(fr.ok());
    out.push_back(std::move(*fr));
  }
  return out;
}

}  // namespace

TEST_CASE("morph: the space-time method gives closed, non-empty meshes", "[morph]") {
  for (const MorphFrame& fr : spaceTimeFrames()) {
    INFO("t = " << fr.timeSec);
    CHECK(fr.mesh.triangleCount() > 100);  // the default blend keeps a shape between the stand-ins
    const MeshTopology topo = analyzeMesh(fr.mesh);
    CHECK(topo.boundaryEdges == 0);
    CHECK(topo.degenerateTriangles == 0);
  }
}

// Frame 75 at 24^3 used to have 2 non-manifold edges: both cells sharing an
// ambiguous face drew the same triangle in it (see the polygoniser's tests).
TEST_CASE("morph: the space-time method gives manifold meshes", "[morph]") {
  for (const MorphFrame& fr : spaceTimeFrames()) {
    INFO("t = " << fr.timeSec);
    const MeshTopology topo = analyzeMesh(fr.mesh);
    CHECK(topo.nonManifoldEdges == 0);
    CHECK(topo.manifold());
  }
}

TEST_CASE("morph: the transitions meet the implicit morph at B and C within a grid cell", "[morph]") {
  const auto& rt = *test::demoMorph().runtime;
  for (bool atB : {true, false}) {
    auto gap = measureSeamGap(rt, atB, 40);
    REQUIRE(gap.ok());
    INFO((atB ? "B" : "C") << ": max gap " << gap->maxDistance << " m, cell " << gap->cellSize << " m");
    CHECK(gap->maxDistance < gap->cellSize);
    CHECK(gap->meanDistance < 0.25 * gap->cellSize);
  }
}

TEST_CASE("morph: solid noise displaces along normals, deterministically, keeping connectivity", "[morph]") {
  CHECK(solidNoise({1.0f, 2.0f, 3.0f}) == 0.0f);  // zero on the lattice
  float lo = 1.0f, hi = -1.0f;
  for (const auto& x : samplePoints(500)) {
    const float v = solidNoise(x * 7.3f);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    CHECK(solidNoise(x * 7.3f) == v);
  }
  CHECK(lo < -0.2f);
  CHECK(hi > 0.2f);
  const auto& rt = *test::demoMorph().runtime;
  MorphFrameSettings fs;
  fs.resolution = 24;
  auto fr = evaluateMorphFrame(rt, rt.timeline.frameToSec((rt.setup.markers.b + rt.setup.markers.c) / 2), fs);
  REQUIRE(fr.ok());
  TriangleMesh m = fr->mesh;
  displaceBySolidNoise(m, 0.01f, 10.0f);
  CHECK(m.indices == fr->mesh.indices);
  double moved = 0.0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const float d = glm::length(m.positions[i] - fr->mesh.positions[i]);
    CHECK(d <= 0.0101f);
    moved += d;
  }
  CHECK(moved > 0.0);
}

TEST_CASE("morph: user-controlled segment tracks change the morph", "[morph]") {
  Project p = test::demoMorph().project;
  // Collapse every creature segment to nothing in the middle of the morph.
  ActorMorph& src = *p.morph.findActor(p.morph.sourceActorId);
  for (int i = 0; i < static_cast<int>(src.standin.segments.size()); ++i) {
    SegmentTracks st;
    st.segment = i;
    st.radiusScale.clearKeys();
    st.radiusScale.setKey(0.0, 1.0f, KeyInterp::Linear);
    st.radiusScale.setKey(0.5, 0.0f, KeyInterp::Linear);
    st.radiusScale.setKey(1.0, 1.0f, KeyInterp::Linear);
    src.segmentTracks.push_back(st);
  }
  AssetCache assets;
  auto rt = prepareMorph(p, test::demoMorph().dir, assets);
  REQUIRE(rt.ok());
  const double mid = p.timeline.frameToSec((p.morph.markers.b + p.morph.markers.c) / 2.0);
  const MorphOperand keyed = posedOperand((*rt)->source, mid, 0.5);
  for (const auto& s : keyed.segments) CHECK(s.weightScale == 0.0f);
  const MorphOperand plain = posedOperand((*rt)->source, mid, -1.0);
  for (const auto& s : plain.segments) CHECK(s.weightScale == 1.0f);
  // The weights reach the field: the mid-morph frame, with the creature's side gone, encloses much
  // less than the same frame without the tracks.
  auto untracked = prepareMorph(test::demoMorph().project, test::demoMorph().dir, assets);
  REQUIRE(untracked.ok());
  MorphFrameSettings fs;
  fs.resolution = 32;
  auto keyedFrame = evaluateMorphFrame(**rt, mid, fs);
  auto plainFrame = evaluateMorphFrame(**untracked, mid, fs);
  REQUIRE(keyedFrame.ok());
  REQUIRE(plainFrame.ok());
  REQUIRE(keyedFrame->stage == MorphStage::Morph);
  const double keyedVolume = meshVolume(keyedFrame->mesh), plainVolume = meshVolume(plainFrame->mesh);
  INFO("mid-morph volume with the tracks " << keyedVolume << ", without " << plainVolume);
  CHECK(plainVolume > 0.0);
  CHECK(keyedVolume < 0.5 * plainVolume);
}

TEST_CASE("prepareMorph keeps the bindings of actors an edit did not touch", "[morph]") {
  // The editor prepares a runtime per document revision; binding every vertex is the costly part
  // and depends on the character, its clip and loop, its stand-in and the projection settings.
  const test::DemoMorph& demo = test::demoMorph();
  const std::string baseDir = std::filesystem::path(demo.projectPath).parent_path().string();
  AssetCache assets;
  auto first = prepareMorph(demo.project, baseDir, assets);
  REQUIRE(first.ok());
  auto sameBinding = [](const MorphActorRuntime& a, const MorphActorRuntime& b) {
    return a.binding.offsets == b.binding.offsets && a.binding.standinNormals == b.binding.standinNormals;
  };
  // The noise and the timing: both bindings carried over, equal to binding again.
  Project edited = demo.project;
  edited.morph.noiseAmplitude = FloatTrack(0.02f);
  edited.morph.markers.c += 4;
  auto kept = prepareMorph(edited, baseDir, assets, first->get());
  REQUIRE(kept.ok());
  auto fresh = prepareMorph(edited, baseDir, assets);
  REQUIRE(fresh.ok());
  CHECK((*kept)->setup.markers.c == demo.project.morph.markers.c + 4);
  CHECK((*kept)->source.bindingKept);
  CHECK((*kept)->target.bindingKept);
  CHECK_FALSE((*fresh)->source.bindingKept);
  CHECK(sameBinding((*kept)->source, (*fresh)->source));
  CHECK(sameBinding((*kept)->target, (*fresh)->target));
  CHECK((*kept)->source.binding.offsets.data() != (*first)->source.binding.offsets.data());  // a copy, not shared
  // A stand-in edit binds that actor again: the result differs from the earlier binding.
  Project thicker = demo.project;
  ActorMorph* am = nullptr;
  for (ActorMorph& a : thicker.morph.actors)
    if (a.actorId == thicker.morph.sourceActorId) am = &a;
  REQUIRE(am);
  for (StandinSegment& seg : am->standin.segments) seg.radius *= 1.3f;
  auto rebound = prepareMorph(thicker, baseDir, assets, first->get());
  REQUIRE(rebound.ok());
  CHECK_FALSE((*rebound)->source.bindingKept);
  CHECK((*rebound)->target.bindingKept);
  CHECK_FALSE(sameBinding((*rebound)->source, (*first)->source));
  CHECK(sameBinding((*rebound)->target, (*first)->target));
  auto reboundFresh = prepareMorph(thicker, baseDir, assets);
  REQUIRE(reboundFresh.ok());
  CHECK(sameBinding((*rebound)->source, (*reboundFresh)->source));
}
