#include <catch2/catch.hpp>

#include <filesystem>

#include "core/field/skeleton.h"
#include "core/io/gltf_export.h"
#include "core/io/gltf_import.h"
#include "core/standin/character_pose.h"
#include "core/standin/fit_standin.h"
#include "core/standin/standin_json.h"
#include "util/morph_fixtures.h"
#include "util/temp_dir.h"
#include "util/test_skip.h"

using namespace animorph;

namespace {

// The bounds this suite holds every automatic fit to (relative to the
// bounding-box diagonal of the fitted pose).
constexpr double kMeanFitBound = 0.04;
constexpr double kMaxFitBound = 0.20;

void checkSegmentsOnRig(const Character& c, const Standin& s) {
  const auto rig = rigNodes(c);
  for (const auto& seg : s.segments) {
    REQUIRE(seg.node >= 0);
    REQUIRE(seg.node < static_cast<int>(c.nodes.size()));
    CHECK(rig[size_t(seg.node)]);
    CHECK(seg.radius > 0.0f);
    CHECK(glm::length(seg.b - seg.a) > 0.0f);
  }
}

}  // namespace

TEST_CASE("fit: the demo creature gets one segment per bone and fits closely", "[standin]") {
  const Character& c = test::demoCreature();
  auto fit = fitStandin(c);
  REQUIRE(fit.ok());
  const FitReport& r = fit->report;
  INFO("mean " << r.meanError << " max " << r.maxError << " segments " << r.segments);
  CHECK(r.segments >= 12);
  CHECK(r.segments <= 30);
  CHECK(r.meanError < kMeanFitBound);
  CHECK(r.maxError < kMaxFitBound);
  CHECK(r.projection.failures == 0);
  checkSegmentsOnRig(c, fit->standin);
}

TEST_CASE("fit: the shared Blender characters fit within the stated bounds", "[standin]") {
  const std::string dir = ANIMORPH_SHARED_ASSETS;
  for (const char* name : {"tentacle.glb", "plate.glb"})
    if (!std::filesystem::exists(dir + "/" + name)) ANIMORPH_SKIP(dir << "/" << name << " not present");
  for (const char* name : {"tentacle.glb", "plate.glb"}) {
    auto c = importGltf(dir + "/" + name);
    REQUIRE(c.ok());
    auto fit = fitStandin(*c);
    REQUIRE(fit.ok());
    INFO(name << ": mean " << fit->report.meanError << " max " << fit->report.maxError);
    CHECK(fit->report.segments >= 1);
    CHECK(fit->report.meanError < kMeanFitBound);
    CHECK(fit->report.maxError < kMaxFitBound);
    checkSegmentsOnRig(*c, fit->standin);
  }
}

TEST_CASE("fit: the stand-in follows the skeleton when posed", "[standin]") {
  const Character& c = test::demoCreature();
  auto fit = fitStandin(c);
  REQUIRE(fit.ok());
  const AnimationClip& walk = c.clips[0];
  // At a walk frame every stand-in end moves exactly as its node does.
  const CharacterPose rest = poseCharacter(c, nullptr, 0.0f, glm::mat4(1.0f));
  const CharacterPose posed = poseCharacter(c, &walk, 0.6f, glm::mat4(1.0f));
  const auto a = poseStandin(fit->standin, rest.globals, glm::mat4(1.0f));
  const auto b = poseStandin(fit->standin, posed.globals, glm::mat4(1.0f));
  float moved = 0.0f;
  for (size_t i = 0; i < a.size(); ++i) {
    const int node = fit->standin.segments[i].node;
    const glm::mat4 delta = posed.globals[size_t(node)] * glm::inverse(rest.globals[size_t(node)]);
    CHECK(glm::length(glm::vec3(delta * glm::vec4(a[i].a, 1.0f)) - b[i].a) < 1e-4f);
    moved = std::max(moved, glm::length(a[i].b - b[i].b));
  }
  CHECK(moved > 0.01f);  // the walk does move bones
}

TEST_CASE("fit: capsule stand-ins put the surface at each radius", "[standin]") {
  for (StandinKind kind : {StandinKind::CapsuleUnion, StandinKind::CapsuleBlend}) {
    PosedSegment s{{0, 0, 0}, {1, 0, 0}, 0.2f, 1.0f};
    const FieldProgram p = standinProgram(kind, 10.0f, {s});
    CHECK(test::fieldAt(p, {0.5f, 0.2f, 0.0f}) == Approx(0.0f).margin(1e-5));
    CHECK(test::fieldAt(p, {1.2f, 0.0f, 0.0f}) == Approx(0.0f).margin(1e-5));
    CHECK(test::fieldAt(p, {0.5f, 0.1f, 0.0f}) > 0.0f);
    CHECK(test::fieldAt(p, {0.5f, 0.3f, 0.0f}) < 0.0f);
  }
  // Union: two overlapping capsules keep each one's surface; blend: it swells.
  PosedSegment s1{{0, 0, 0}, {1, 0, 0}, 0.2f, 1.0f}, s2{{0.5f, -1, 0}, {0.5f, 1, 0}, 0.2f, 1.0f};
  const FieldProgram u = standinProgram(StandinKind::CapsuleUnion, 10.0f, {s1, s2});
  const FieldProgram b = standinProgram(StandinKind::CapsuleBlend, 10.0f, {s1, s2});
  const glm::vec3 corner(0.5f + 0.2f, 0.2f, 0.0f);  // on both surfaces' union boundary? no: inside neither, near both
  CHECK(test::fieldAt(u, {0.3f, 0.2f, 0.0f}) == Approx(0.0f).margin(1e-5));
  CHECK(test::fieldAt(b, corner) > test::fieldAt(u, corner));
}

TEST_CASE("fit: the convolution radius rule puts a long segment's surface at its radius", "[standin]") {
  PosedSegment s{{-5, 0, 0}, {5, 0, 0}, 0.1f, 1.0f};
  const FieldProgram p = standinProgram(StandinKind::Convolution, 20.0f, {s});
  CHECK(test::fieldAt(p, {0.0f, 0.1f, 0.0f}) == Approx(0.0f).margin(1e-4));
  // A weight scale below 1 shrinks it; 0 removes it.
  PosedSegment half = s;
  half.weightScale = 0.5f;
  CHECK(test::fieldAt(standinProgram(StandinKind::Convolution, 20.0f, {half}), {0.0f, 0.1f, 0.0f}) < 0.0f);
  PosedSegment gone = s;
  gone.weightScale = 0.0f;
  CHECK(test::fieldAt(standinProgram(StandinKind::Convolution, 20.0f, {gone}), {0.0f, 0.0f, 0.0f}) ==
        Approx(-kStandinThreshold));
}

TEST_CASE("standin JSON: round trip and bad values named", "[standin]") {
  auto fit = fitStandin(test::demoGear());
  REQUIRE(fit.ok());
  Standin s = fit->standin;
  s.kind = StandinKind::CapsuleBlend;
  auto back = standinFromJson(standinToJson(s), "s");
  REQUIRE(back.ok());
  CHECK(*back == s);

  auto j = standinToJson(s);
  j["segments"][1]["radius"] = -1.0;
  auto bad = standinFromJson(j, "x.json: standin");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error() == "x.json: standin.segments[1].radius: must be a positive number (metres)");
  j = standinToJson(s);
  j["kind"] = "blobby";
  CHECK_THAT(standinFromJson(j, "s").error(), Catch::Contains("s.kind"));
  j = standinToJson(s);
  j["segments"][0]["a"] = {1, 2};
  CHECK_THAT(standinFromJson(j, "s").error(), Catch::Contains("s.segments[0].a"));
  // Finite as a double but not as a float (found by fuzzing): refused, not read as inf.
  j = standinToJson(s);
  j["segments"][0]["b"] = {0.0, 1e306, 0.28};
  CHECK_THAT(standinFromJson(j, "s").error(), Catch::Contains("s.segments[0].b"));
  j = standinToJson(s);
  j["segments"][0]["radius"] = 1e300;
  CHECK_THAT(standinFromJson(j, "s").error(), Catch::Contains("s.segments[0].radius"));

  test::TempDir dir;
  const std::string path = dir.file("gear.standin.json");
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    const std::string text = standinFileText(s, "gear.glb", nlohmann::json::object());
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  auto loaded = loadStandinFile(path);
  REQUIRE(loaded.ok());
  CHECK(*loaded == s);
}

TEST_CASE("fit: a skin-less glTF is a rigid one-bone actor, an animation-less one a static pose", "[standin]") {
  // The creature's mesh exported without its skin and its clip.
  Character c = test::demoCreature();
  for (auto& n : c.nodes) n.skin = -1;
  c.skins.clear();
  c.clips.clear();
  for (auto& m : c.meshes) {
    m.joints0.clear();
    m.weights0.clear();
    m.joints1.clear();
    m.weights1.clear();
  }
  test::TempDir dir;
  REQUIRE(exportGlb(c, dir.file("rigid.glb")).ok());
  auto imported = importGltf(dir.file("rigid.glb"));
  REQUIRE(imported.ok());
  REQUIRE(imported->skins.empty());
  auto fit = fitStandin(*imported);
  REQUIRE(fit.ok());
  // One segment along the vertices' principal axis; the repair of a poor first fit may re-place
  // it as several side by side, all on the mesh's node.
  REQUIRE(!fit->standin.segments.empty());
  CHECK((fit->standin.segments.size() == 1 || !fit->report.repairs.empty()));
  const int meshNode = imported->meshNodes().at(0);
  for (const auto& seg : fit->standin.segments) CHECK(seg.node == meshNode);
  // One note says the segment follows the principal axis; a second may say a repair was tried.
  std::string notes;
  for (const auto& n : fit->report.notes) notes += n + "\n";
  INFO("notes: " << notes);
  REQUIRE(!fit->report.notes.empty());
  CHECK(fit->report.notes[0].find("principal axis") != std::string::npos);
  for (size_t i = 1; i < fit->report.notes.size(); ++i)
    CHECK(fit->report.notes[i].find("automatic repair tried") != std::string::npos);
  CHECK(fit->report.notes.size() <= 2);
  CHECK(fit->report.projection.failures == 0);
}
