#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "core/standin_morph/transition.h"
#include "core/rig/pose.h"
#include "core/rig/skinning.h"
#include "core/standin/fit_standin.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

struct Bound {
  Standin standin;
  StandinBinding binding;
};

const Bound& creatureBound() {
  static const Bound b = [] {
    auto fit = fitStandin(test::demoCreature());
    if (!fit) throw std::runtime_error(fit.error());
    Bound r;
    r.standin = fit->standin;
    r.binding = bindToStandin(test::demoCreature(), r.standin, nullptr, 0.0f, ProjectionSettings{});
    return r;
  }();
  return b;
}

}  // namespace

TEST_CASE("transition: at alpha = 0 it is plain skinning, exactly", "[transition]") {
  const Character& c = test::demoCreature();
  const AnimationClip& walk = c.clips[0];
  for (float t : {0.0f, 0.55f, 1.3f}) {
    const auto globals = poseGlobals(c, &walk, t);
    std::vector<float> alpha(c.totalVertices(), 0.0f);
    std::vector<glm::vec3> pos, nrm;
    evaluateTransition(c, creatureBound().binding, globals, glm::mat4(1.0f), alpha, nullptr, nullptr, {}, pos, nrm);
    const auto ref = skinnedWorldPositions(c, &walk, t);
    REQUIRE(pos.size() == ref.size());
    size_t differ = 0;
    for (size_t i = 0; i < pos.size(); ++i) differ += pos[i] != ref[i];
    CHECK(differ == 0);
  }
}

TEST_CASE("transition: at alpha = 1 the vertices lie on the posed stand-in", "[transition]") {
  const Character& c = test::demoCreature();
  const AnimationClip& walk = c.clips[0];
  const Bound& b = creatureBound();
  const float t = 0.9f;  // a walk pose far from the rest pose the vertices were bound in
  const auto globals = poseGlobals(c, &walk, t);
  const glm::mat4 root = glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.0f, -0.2f));
  const auto segs = poseStandin(b.standin, globals, root);
  const FieldProgram prog = standinProgram(b.standin.kind, b.standin.sharpness, segs);
  std::vector<float> alpha(c.totalVertices(), 1.0f);
  std::vector<glm::vec3> raw, pos, nrm;
  evaluateTransition(c, b.binding, globals, root, alpha, nullptr, nullptr, {}, raw, nrm);
  const TransitionStats st = evaluateTransition(c, b.binding, globals, root, alpha, &prog, &segs, {}, pos, nrm);
  CHECK(st.reprojected == c.totalVertices());
  float worstRaw = 0.0f, worst = 0.0f;
  size_t onSurface = 0;
  for (size_t i = 0; i < pos.size(); ++i) {
    worstRaw = std::max(worstRaw, std::abs(test::fieldAt(prog, raw[i])));
    const float f = std::abs(test::fieldAt(prog, pos[i]));
    worst = std::max(worst, f);
    onSurface += f < 1e-4f;
  }
  INFO("skinning drift |f| up to " << worstRaw << ", after re-projection " << worst);
  CHECK(worstRaw > 1e-3f);  // drift exists without re-projection...
  CHECK(double(onSurface) >= 0.99 * double(pos.size()));  // ...and is gone with it
  CHECK(worst < 1e-2f);
}

TEST_CASE("transition: alpha follows the easing, a painted region collapses first", "[transition]") {
  const FloatTrack ease = smoothstepTrack();
  CHECK(ease.evaluate(0.25) == Approx(3 * 0.0625 - 2 * 0.015625));
  std::vector<float> a;
  transitionAlphas(0.5, ease, {}, 0.5f, false, 3, a);
  CHECK(a[0] == Approx(0.5f));
  transitionAlphas(0.5, ease, {}, 0.5f, true, 3, a);
  CHECK(a[2] == Approx(0.5f));

  const std::vector<float> map{1.0f, 0.0f, 0.5f};
  std::vector<float> prev(3, 0.0f);
  double paintedDone = -1.0, restDone = -1.0;
  for (int k = 0; k <= 100; ++k) {
    const double u = k / 100.0;
    transitionAlphas(u, ease, map, 0.5f, false, 3, a);
    for (int i = 0; i < 3; ++i) CHECK(a[size_t(i)] >= prev[size_t(i)]);  // monotone
    if (paintedDone < 0 && a[0] >= 1.0f) paintedDone = u;
    if (restDone < 0 && a[1] >= 1.0f) restDone = u;
    CHECK(a[0] >= a[2]);
    CHECK(a[2] >= a[1]);
    prev = a;
  }
  CHECK(paintedDone == Approx(0.5));
  CHECK(restDone == Approx(1.0));
  transitionAlphas(0.0, ease, map, 0.5f, false, 3, a);
  CHECK(a == std::vector<float>{0.0f, 0.0f, 0.0f});
  // Expansion: painted vertices leave the stand-in first.
  transitionAlphas(0.3, ease, map, 0.5f, true, 3, a);
  CHECK(a[0] < a[1]);
}

TEST_CASE("transition: the painted region of the creature reaches the stand-in first", "[transition]") {
  const Character& c = test::demoCreature();
  const Bound& b = creatureBound();
  // Paint the tail (vertices behind z = -0.3).
  std::vector<float> map(c.totalVertices(), 0.0f);
  for (size_t i = 0; i < map.size(); ++i) map[i] = c.meshes[0].positions[i].z < -0.3f ? 1.0f : 0.0f;
  const auto globals = poseGlobals(c, nullptr, 0.0f);
  std::vector<float> alpha;
  transitionAlphas(0.6, smoothstepTrack(), map, 0.5f, false, map.size(), alpha);
  std::vector<glm::vec3> pos, nrm, start;
  std::vector<float> zero(map.size(), 0.0f);
  evaluateTransition(c, b.binding, globals, glm::mat4(1.0f), zero, nullptr, nullptr, {}, start, nrm);
  evaluateTransition(c, b.binding, globals, glm::mat4(1.0f), alpha, nullptr, nullptr, {}, pos, nrm);
  double paintedLeft = 0.0, restLeft = 0.0;
  size_t np = 0, nr = 0;
  for (size_t i = 0; i < map.size(); ++i) {
    const glm::vec3 end = start[i] + b.binding.offsets[i];  // rest pose: bind space is world space
    const double left = glm::length(end - pos[i]);
    if (map[i] > 0.5f) { paintedLeft += left; ++np; }
    else { restLeft += left; ++nr; }
  }
  REQUIRE(np > 0);
  REQUIRE(nr > 0);
  CHECK(paintedLeft / double(np) < 1e-5);       // already on the stand-in at u = 0.6
  CHECK(restLeft / double(nr) > 1e-3);          // the rest is still on its way
}
