// Aligning a morph's target to its source by units first (morph/target_alignment.h) and what
// animorph-cli new says and refuses (morph/new_morph_project.h).
#include <catch2/catch.hpp>

#include "demo/creature.h"
#include "core/project/new_morph_project.h"
#include "core/standin_morph/target_alignment.h"

using namespace animorph;

namespace {

// The creature with every root scaled k times (its lengths in a unit 1/k m), unit as given.
Character scaledBy(Character c, float k, LengthUnit unit) {
  for (int r : c.roots) c.nodes[r].rest.scale *= k, c.nodes[r].rest.translation *= k;
  c.unit = unit;
  return c;
}

// The creature as a file in centimetres would hold it: every root scaled 100x, unit declared.
Character inCentimetres(const Character& c) { return scaledBy(c, 100.0f, {0.01, "centimetres", true}); }

}  // namespace

TEST_CASE("target alignment: a centimetre target is scaled by its unit alone, and says so", "[morph][units]") {
  const Character metres = makeCreatureCharacter();
  const Character cm = inCentimetres(metres);
  const TargetAlignment a = alignTargetToSource(metres, cm);
  CHECK(a.unitScale == Approx(0.01));
  CHECK(a.sizeRatio == Approx(1.0).epsilon(1e-4));
  CHECK_FALSE(a.resize);
  CHECK_FALSE(a.needsConsent);
  CHECK(a.transform.scale.x == Approx(0.01f));
  CHECK(a.unitNote == "target in centimetres, scaled by 0.01 to the source's metres");
  // The other way round: metres into a centimetre source, 100x.
  const TargetAlignment back = alignTargetToSource(cm, metres);
  CHECK(back.unitScale == Approx(100.0));
  CHECK(back.unitNote == "target in metres, scaled by 100 to the source's centimetres");
  CHECK(unitsOnly(back).scale.y == Approx(100.0f));
}

TEST_CASE("new: units explain a 100x size difference, declared or not, a 300x that no unit explains is refused",
          "[morph][units]") {
  const Character metres = makeCreatureCharacter();
  NewMorphSettings s;
  s.acceptPoorFit = true;  // the fit is not what this test is about
  auto made = makeMorphProject(metres, "walker.glb", inCentimetres(metres), "walker_cm.fbx", s);
  REQUIRE(made.ok());
  CHECK(made->scaleApplied == Approx(0.01));
  CHECK(std::find(made->messages.begin(), made->messages.end(),
                  "target in centimetres, scaled by 0.01 to the source's metres") != made->messages.end());
  CHECK(made->warnings.empty());

  // glTF holding centimetre numbers (it declares metres) and a file that declares no unit: the 100x
  // is taken as centimetres, scaled by exactly 0.01 and said so.
  for (const LengthUnit& unit : {LengthUnit{}, LengthUnit{1.0, "metres (assumed)", false}}) {
    auto guessed = makeMorphProject(metres, "walker.glb", scaledBy(metres, 100.0f, unit), "big.glb", s);
    REQUIRE(guessed.ok());
    CHECK(guessed->scaleApplied == Approx(0.01));
    CHECK(guessed->warnings.empty());
    CHECK(std::find(guessed->messages.begin(), guessed->messages.end(),
                    "target is 100x its partner (probably authored in centimetres): scaled by 0.01") !=
          guessed->messages.end());
  }
  // The source in millimetre numbers: the target is scaled up by 1000.
  const TargetAlignment up = alignTargetToSource(scaledBy(metres, 1000.0f, {}), metres);
  CHECK(up.unitScale == Approx(1000.0));
  CHECK(up.guessedScale == Approx(1000.0));
  CHECK_FALSE(up.needsConsent);
  CHECK(up.unitNote == "target is 0.001x its partner (the partner probably authored in millimetres): scaled by 1000");
  // A file that declares centimetres is not guessed again: 100x more than its unit needs consent.
  const TargetAlignment declared = alignTargetToSource(metres, scaledBy(metres, 10000.0f, {0.01, "centimetres", true}));
  CHECK(declared.guessedScale == 1.0);
  CHECK(declared.needsConsent);

  // 300x and 13x: between the units' factors, beyond the tolerance of each.
  for (const float k : {300.0f, 13.0f}) {
    INFO("x" << k);
    auto refused = makeMorphProject(metres, "walker.glb", scaledBy(metres, k, {}), "big.glb", s);
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error(), Catch::StartsWith("big.glb: aligning the target to the source needs a scale of"));
    CHECK_THAT(refused.error(), Catch::Contains("which no unit explains"));
    s.allowLargeRescale = true;
    auto allowed = makeMorphProject(metres, "walker.glb", scaledBy(metres, k, {}), "big.glb", s);
    s.allowLargeRescale = false;
    REQUIRE(allowed.ok());
    CHECK(allowed->scaleApplied == Approx(1.0 / k).epsilon(1e-3));
    CHECK_FALSE(allowed->warnings.empty());
  }
}
