// Clicking the morph's own surface (pickMorphSurface): during the collapse,
// the implicit stage and the expansion the surface under the cursor selects
// the actor it comes from; before A and after D the morph answers nothing (the
// actors are picked as themselves); a ray that misses finds nothing.
#include <catch2/catch.hpp>

#include "editor/morph_pick.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

// A ray 1 m outside the centre of a triangle of the morph's mesh at timeSec, aimed back at it.
Ray rayAtSurface(const MorphRuntime& rt, double timeSec) {
  MorphFrameSettings fs;
  fs.resolution = 48;
  auto fr = evaluateMorphFrame(rt, timeSec, fs);
  REQUIRE(fr.ok());
  const TriangleMesh& m = fr->mesh;
  REQUIRE(m.triangleCount() > 0);
  const size_t t = m.triangleCount() / 2;
  const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                  c = m.positions[m.indices[3 * t + 2]];
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  return Ray{(a + b + c) / 3.0f + n, -n};
}

}  // namespace

TEST_CASE("morph pick: the shown surface selects its actor at every stage", "[morph][pick]") {
  const auto& demo = test::demoMorph();
  const MorphRuntime& rt = *demo.runtime;
  const Timeline& tl = demo.project.timeline;
  const MorphMarkers mk = rt.setup.markers;
  struct Case {
    double frame;
    std::string owner;
  };
  for (const Case& c : {Case{(mk.a + mk.b) / 2.0, rt.setup.sourceActorId}, Case{(mk.b + mk.c) / 2.0, rt.setup.sourceActorId},
                        Case{(mk.c + mk.d) / 2.0, rt.setup.targetActorId}}) {
    const double t = tl.frameToSec(c.frame);
    const Ray ray = rayAtSurface(rt, t);
    auto hit = pickMorphSurface(rt, t, ray, nullptr);
    INFO("frame " << c.frame);
    REQUIRE(hit);
    CHECK(hit->actorId == c.owner);
    CHECK(hit->distance <= 1.0f + 1e-3f);
    // Aimed away from the surface: nothing (the mesh is closed and the ray starts outside).
    CHECK_FALSE(pickMorphSurface(rt, t, Ray{ray.origin, -ray.direction}, nullptr));
  }
  // The implicit stage uses the preview's mesh when there is one: an empty one falls back to polygonising.
  const double tm = tl.frameToSec((mk.b + mk.c) / 2.0);
  TriangleMesh empty;
  CHECK(pickMorphSurface(rt, tm, rayAtSurface(rt, tm), &empty));
  // Before A and after D the actors are drawn (and picked) as themselves.
  const Ray any{glm::vec3(0.0f, 0.5f, 5.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
  CHECK_FALSE(pickMorphSurface(rt, tl.frameToSec(mk.a - 1), any, nullptr));
  CHECK_FALSE(pickMorphSurface(rt, tl.frameToSec(mk.d + 1), any, nullptr));
}
