// Stand-ins fitted to the test characters (tests/tools/make_test_characters.py): Blender's own
// exports of automatically weighted rigs -- a humanoid with face and finger bones and three meshes,
// a quadruped with a wide body on one spine bone, a long tentacle, a 1 cm thin flag; root, IK and
// helper bones outside the mesh; metres, centimetres, scaled and stretched roots. Every one gets a
// stand-in in one piece with a fit report that is not poor, repaired where the first fit was poor.
// Hidden from discovery ([.testchars]): tests/CMakeLists.txt runs them after the "test characters"
// fixture has made the files (ANIMORPH_TEST_CHARACTERS), skipped when Blender is missing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/io/character_import.h"
#include "core/standin/character_pose.h"
#include "core/standin/fit_standin.h"
#include "core/standin/repair_fit.h"
#include "util/test_characters.h"
#include "util/test_skip.h"

using namespace animorph;

namespace {

const std::filesystem::path kDir = ANIMORPH_TEST_CHARACTERS;

// The manifest's entries whose files this build can import (glTF, FBX, Collada).
std::vector<nlohmann::json> importableCharacters() {
  std::vector<nlohmann::json> out;
  for (const auto& e : test::testCharacterEntries(kDir.string()))
    if (characterFormatOf(e["file"].get<std::string>()) != CharacterFormat::Unknown) out.push_back(e);
  return out;
}

}  // namespace

TEST_CASE("fit: every test character (Blender exports) gets a one-piece stand-in that is not poor",
          "[.testchars][standin]") {
  const auto entries = importableCharacters();
  if (entries.empty()) ANIMORPH_SKIP("no test characters in " << kDir.string() << " (Blender missing?)");
  size_t repaired = 0, fitted = 0;
  for (const auto& e : entries) {
    const std::string file = (kDir / e["file"].get<std::string>()).string();
    auto c = importCharacter(file);
    INFO(file << ": " << (c.ok() ? std::string("read") : c.error()));
    REQUIRE(c.ok());
    ++fitted;
    auto fit = fitStandin(*c);
    REQUIRE(fit.ok());
    const FitReport& r = fit->report;
    INFO(file << ": " << fitSummary(r));
    INFO(repairSummary(r));
    for (const auto& p : r.problems) INFO("problem: " << p);
    // Each mesh is one piece; the stand-in is one piece over them all.
    CHECK(r.meshComponents == int(e["meshes"].size()));
    CHECK(r.standinComponents == 1);
    CHECK(r.largestGap == 0.0);
    CHECK(!r.poor);
    CHECK(r.projection.failureDistances.size() == r.projection.failures);
    CHECK(r.projectionMisses <= r.projection.failures);
    CHECK(r.meanError < 0.04);
    CHECK(r.segments == fit->standin.segments.size());
    CHECK(r.perSegment.size() == r.segments);
    CHECK(r.diagonal == Approx(poseBounds(*c).diagonal()).epsilon(1e-4));
    if (!r.repairs.empty()) {
      ++repaired;
      CHECK(r.beforeRepair.poor);
      CHECK(r.beforeRepair.farShare + 1e-9 >= r.farShare);
    }
  }
  // Repairs are not free: the report says how many characters needed one.
  CHECK(fitted >= 30);  // every glTF, FBX and Collada file of the set
  std::cout << "test characters: " << fitted << " of " << entries.size() << " fitted, " << repaired << " repaired\n";
}

// The quadruped's first fit is poor in both units; the spine's repair was refused in centimetres
// for one vertex whose projection stopped within float noise of the surface (|f| 1.4e-5 against a
// tolerance of 1e-5): such a failure is no miss (FitQualitySettings::surfaceNoiseFraction).
TEST_CASE("fit: the quadruped in centimetres (Collada) fits like the one in metres, repair included",
          "[.testchars][standin]") {
  const std::string mFile = (kDir / "quadruped_m.dae").string(), cmFile = (kDir / "quadruped_cm.dae").string();
  for (const auto& f : {mFile, cmFile})
    if (!std::filesystem::exists(f)) ANIMORPH_SKIP("no " << f << " (Blender missing?)");
  auto m = importCharacter(mFile);
  auto cm = importCharacter(cmFile);
  REQUIRE(m.ok());
  REQUIRE(cm.ok());
  REQUIRE(cm->unit.metresPerUnit == Approx(0.01));
  auto a = fitStandin(*m);
  auto b = fitStandin(*cm);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  const FitReport &ra = a->report, &rb = b->report;
  INFO("metres: " << fitSummary(ra) << " / " << repairSummary(ra));
  INFO("centimetres: " << fitSummary(rb) << " / " << repairSummary(rb));
  CHECK(rb.diagonal == Approx(100.0 * ra.diagonal).epsilon(1e-4));
  CHECK(!ra.poor);
  CHECK(!rb.poor);
  CHECK(rb.segments == ra.segments);
  CHECK(rb.repairs.size() == ra.repairs.size());
  CHECK(rb.standinComponents == 1);
  CHECK(std::abs(rb.farShare - ra.farShare) <= 2e-3);
  CHECK(std::abs(rb.meanError - ra.meanError) <= 1e-3);
  CHECK(ra.projectionMisses == 0);
  CHECK(rb.projectionMisses == 0);
  // Every failure counts as a miss when no noise is allowed: the count is what the projection says.
  FitSettings fs;
  fs.quality.surfaceNoiseFraction = 0.0;
  const CharacterPose pose = poseCharacter(*cm, nullptr, 0.0f, glm::mat4(1.0f));
  const FitReport strict = measureFitQuality(*cm, b->standin, pose, fs.projection, fs.quality);
  CHECK(strict.projectionMisses == strict.projection.failures);
  CHECK(strict.farShare == Approx(rb.farShare));
}

TEST_CASE("fit repair: the wide-bodied quadruped's spine is re-placed side by side, before and after reported",
          "[.testchars][standin]") {
  const std::string file = (kDir / "quadruped_m.glb").string();
  if (!std::filesystem::exists(file)) ANIMORPH_SKIP("no " << file << " (Blender missing?)");
  auto c = importCharacter(file);
  REQUIRE(c.ok());
  FitSettings first;
  first.repair.enabled = false;
  auto plain = fitStandin(*c, first);
  auto fixed = fitStandin(*c);
  REQUIRE(plain.ok());
  REQUIRE(fixed.ok());
  INFO("first: " << fitSummary(plain->report));
  INFO("repaired: " << fitSummary(fixed->report) << " / " << repairSummary(fixed->report));
  CHECK(!fixed->report.poor);
  CHECK(fixed->report.standinComponents == 1);
  if (plain->report.poor) {
    // The repair names what it did and keeps the first fit's figures.
    REQUIRE(!fixed->report.repairs.empty());
    CHECK(fixed->report.beforeRepair.farShare == Approx(plain->report.farShare));
    CHECK(fixed->report.farShare < plain->report.farShare);
    CHECK(repairSummary(fixed->report).find("->") != std::string::npos);
  }
  // The spine carries several segments side by side (the body is wider than one tube).
  int spine = -1;
  for (size_t n = 0; n < c->nodes.size(); ++n)
    if (c->nodes[n].name == "spine") spine = int(n);
  REQUIRE(spine >= 0);
  const auto onSpine = std::count_if(fixed->standin.segments.begin(), fixed->standin.segments.end(),
                                     [&](const StandinSegment& s) { return s.node == spine; });
  CHECK(onSpine >= 2);
}

TEST_CASE("fit repair: a tentacle whose middle segments are removed is bridged back into one piece along the chain",
          "[.testchars][standin]") {
  const std::string file = (kDir / "tentacle_m.glb").string();
  if (!std::filesystem::exists(file)) ANIMORPH_SKIP("no " << file << " (Blender missing?)");
  auto c = importCharacter(file);
  REQUIRE(c.ok());
  auto fit = fitStandin(*c);
  REQUIRE(fit.ok());
  Standin broken = fit->standin;
  std::vector<int> removed;
  for (size_t n = 0; n < c->nodes.size(); ++n)
    if (c->nodes[n].name == "seg04" || c->nodes[n].name == "seg05") removed.push_back(int(n));
  REQUIRE(removed.size() == 2);
  const size_t before = broken.segments.size();
  broken.segments.erase(std::remove_if(broken.segments.begin(), broken.segments.end(),
                                       [&](const StandinSegment& s) {
                                         return std::find(removed.begin(), removed.end(), s.node) != removed.end();
                                       }),
                        broken.segments.end());
  REQUIRE(broken.segments.size() < before);
  const CharacterPose pose = poseCharacter(*c, nullptr, 0.0f, glm::mat4(1.0f));
  const FitSettings fs;
  const FitReport first = measureFitQuality(*c, broken, pose, fs.projection, fs.quality);
  REQUIRE(first.standinComponents == 2);
  REQUIRE(first.poor);
  // Every vertex fitted by its dominant bone (the removed bones' vertices too: they stay uncovered).
  std::vector<int> vertexNode(pose.dominantNode.begin(), pose.dominantNode.end());
  Standin repaired = broken;
  const FitReport r = repairStandinFit(*c, pose, vertexNode, repaired, first, fs.projection, fs.quality,
                                       fs.radiusPercentile, FitRepairSettings{});
  INFO(repairSummary(r));
  CHECK(r.standinComponents == 1);
  CHECK(r.largestGap == 0.0);
  REQUIRE(!r.repairs.empty());
  CHECK(std::any_of(r.repairs.begin(), r.repairs.end(),
                    [](const std::string& a) { return a.find("bridged 'seg0") != std::string::npos; }));
  CHECK(r.beforeRepair.standinComponents == 2);
  CHECK(r.beforeRepair.largestGap > 0.0);
  CHECK(repaired.segments.size() > broken.segments.size());
  // Repair off: nothing changes.
  Standin untouched = broken;
  FitRepairSettings off;
  off.enabled = false;
  const FitReport same = repairStandinFit(*c, pose, vertexNode, untouched, first, fs.projection, fs.quality,
                                          fs.radiusPercentile, off);
  CHECK(untouched == broken);
  CHECK(same.repairs.empty());
}
