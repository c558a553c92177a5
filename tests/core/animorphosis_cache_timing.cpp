// AnimorphosisCache keeps the project's timing with C (computed once per revision, not per scrubbed
// time): C(t)'s preview source must still follow a timing edit once the revision changes.
#include <catch2/catch.hpp>

#include "core/animorphosis/evaluate_generic.h"
#include "core/project/animorphosis_project.h"
#include "core/scene/animorphosis_scene.h"
#include "demo/animorphosis_demo.h"

using namespace animorph;

namespace {

// The preview source's program at timeSec against a fresh compile of C with the project's timing now.
void requireSourceFollowsTiming(AnimorphosisCache& cache, const Project& p, const GenericTree& c, double timeSec,
                                Bounds& bounds) {
  auto source = cache.previewSource(p, timeSec);
  REQUIRE(source);
  auto field = source->field(64);
  REQUIRE(field.ok());
  const FieldProgram ref = compileGeneric(c, animorphosisTiming(p), timeSec);
  REQUIRE(field->fieldProgram().primitiveCount() == ref.primitiveCount());
  CHECK(field->fieldProgram().bounds().min == ref.bounds().min);
  CHECK(field->fieldProgram().bounds().max == ref.bounds().max);
  bounds = field->fieldProgram().bounds();
}

}  // namespace

TEST_CASE("animorphosis cache: C(t)'s preview source follows the project's timing, kept until the revision changes",
          "[animorph][preview]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  AnimorphosisCache cache;
  const int owner = 0;
  auto c = cache.get(*p, &owner, 1);
  REQUIRE(c);
  const double t = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec) + 0.3;
  Bounds before, after;
  requireSourceFollowsTiming(cache, *p, *c, t, before);
  requireSourceFollowsTiming(cache, *p, *c, t + 1.0 / 24.0, before);  // a scrubbed time: the kept timing
  requireSourceFollowsTiming(cache, *p, *c, t, before);

  // The source actor plays at 1.7 times its speed: a new revision, a new timing.
  Actor* source = nullptr;
  for (Actor& a : p->actors)
    if (a.id == p->animorphosis.sourceActorId) source = &a;
  REQUIRE(source);
  source->speed *= 1.7;
  auto edited = cache.get(*p, &owner, 2);
  REQUIRE(edited);
  requireSourceFollowsTiming(cache, *p, *edited, t, after);
  // The edit moved C(t) (its clip time moved), so a timing kept from before would have shown.
  CHECK((after.min != before.min || after.max != before.max));
}
