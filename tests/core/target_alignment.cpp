// Aligning a morph's target to its source by units first (morph/target_alignment.h) and what
// animorph-cli new says and refuses (morph/new_morph_project.h).
#include <catch2/catch.hpp>

#include "demo/creature.h"
#include "core/project/new_morph_project.h"
#include "core/standin_morph/target_alignment.h"

using namespace animorph;

namespace {

// The creature as a file in centimetres would hold it: every root scaled 100x, unit declared.
Character inCentimetres(Character c) {
  for (int r : c.roots) c.nodes[r].rest.scale *= 100.0f, c.nodes[r].rest.translation *= 100.0f;
  c.unit = {0.01, "centimetres", true};
  return c;
}

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

TEST_CASE("new: units explain a 100x size difference, the same difference with no unit is refused", "[morph][units]") {
  const Character metres = makeCreatureCharacter();
  NewMorphSettings s;
  s.acceptPoorFit = true;  // the fit is not what this test is about
  auto made = makeMorphProject(metres, "walker.glb", inCentimetres(metres), "walker_cm.fbx", s);
  REQUIRE(made.ok());
  CHECK(made->scaleApplied == Approx(0.01));
  CHECK(std::find(made->messages.begin(), made->messages.end(),
                  "target in centimetres, scaled by 0.01 to the source's metres") != made->messages.end());
  CHECK(made->warnings.empty());

  Character undeclared = inCentimetres(metres);
  undeclared.unit = {};  // metres: the 100x is no unit's doing
  auto refused = makeMorphProject(metres, "walker.glb", undeclared, "big.glb", s);
  REQUIRE_FALSE(refused.ok());
  CHECK_THAT(refused.error(), Catch::StartsWith("big.glb: aligning the target to the source needs a scale of 0.01x"));
  CHECK_THAT(refused.error(), Catch::Contains("which no unit explains"));
  s.allowLargeRescale = true;
  auto allowed = makeMorphProject(metres, "walker.glb", undeclared, "big.glb", s);
  REQUIRE(allowed.ok());
  CHECK(allowed->scaleApplied == Approx(0.01).epsilon(1e-3));
  CHECK_FALSE(allowed->warnings.empty());
}
