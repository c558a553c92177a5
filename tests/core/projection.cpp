#include <catch2/catch.hpp>

#include "core/standin_morph/transition.h"
#include "core/rig/pose.h"
#include "core/standin/character_pose.h"
#include "core/standin/fit_standin.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

// |f| at every vertex moved by its binding (bind space) under the fitted pose.
std::vector<float> fieldAfterBinding(const Character& c, const Standin& s, const StandinBinding& b,
                                     const AnimationClip* clip, float t) {
  const CharacterPose pose = poseCharacter(c, clip, t, glm::mat4(1.0f));
  const auto segs = poseStandin(s, pose.globals, glm::mat4(1.0f));
  const FieldProgram prog = standinProgram(s.kind, s.sharpness, segs);
  std::vector<float> out;
  FieldEvaluator e;
  for (size_t i = 0; i < pose.positions.size(); ++i) {
    const glm::vec3 p = glm::vec3(pose.vertexMatrices[i] * glm::vec4(glm::vec3(glm::inverse(pose.vertexMatrices[i]) *
                                                                               glm::vec4(pose.positions[i], 1.0f)) +
                                                                         b.offsets[i],
                                                                     1.0f));
    out.push_back(std::abs(e.evaluatePoint(prog, p)));
  }
  return out;
}

double fractionBelow(const std::vector<float>& v, float bound) {
  size_t n = 0;
  for (float x : v) n += x < bound;
  return double(n) / double(std::max<size_t>(1, v.size()));
}

}  // namespace

TEST_CASE("projection: vertices land on f = 0 (rest pose and a clip frame)", "[projection]") {
  for (const Character* c : {&test::demoCreature(), &test::demoGear()}) {
    auto fit = fitStandin(*c);
    REQUIRE(fit.ok());
    const AnimationClip* clip = &c->clips[0];
    for (const AnimationClip* poseClip : {static_cast<const AnimationClip*>(nullptr), clip}) {
      const float t = poseClip ? 0.7f : 0.0f;
      const StandinBinding b = bindToStandin(*c, fit->standin, poseClip, t, ProjectionSettings{});
      REQUIRE(b.offsets.size() == c->totalVertices());
      const auto f = fieldAfterBinding(*c, fit->standin, b, poseClip, t);
      INFO(c->sourcePath << (poseClip ? " at a clip frame" : " at rest") << ": fallbacks " << b.stats.fallbacks
                         << " failures " << b.stats.failures);
      CHECK(fractionBelow(f, 1e-4f) >= 0.99);
      CHECK(b.stats.failures <= b.stats.points / 100);
      for (const auto& n : b.standinNormals) CHECK(glm::length(n) == Approx(1.0f).margin(1e-4));
    }
  }
}

TEST_CASE("projection: onto a capsule the result is the closest surface point", "[projection]") {
  const std::vector<PosedSegment> segs{{{0, 0, 0}, {1, 0, 0}, 0.25f, 1.0f}};
  const FieldProgram p = standinProgram(StandinKind::CapsuleUnion, 10.0f, segs);
  const std::vector<glm::vec3> in{{0.5f, 0.4f, 0.0f}, {0.3f, 0.0f, 0.1f}, {-0.2f, 0.0f, 0.0f}, {0.5f, 0.0f, -0.3f}};
  std::vector<glm::vec3> out(in.size()), nrm(in.size());
  const ProjectionStats st = projectOntoField(p, segs, in.data(), in.size(), out.data(), nrm.data(), {});
  CHECK(st.failures == 0);
  const glm::vec3 expect[] = {{0.5f, 0.25f, 0.0f}, {0.3f, 0.0f, 0.25f}, {-0.25f, 0.0f, 0.0f}, {0.5f, 0.0f, -0.25f}};
  for (size_t i = 0; i < in.size(); ++i) {
    CHECK(glm::length(out[i] - expect[i]) < 1e-4f);
    CHECK(glm::dot(nrm[i], glm::normalize(expect[i] - glm::vec3(glm::clamp(expect[i].x, 0.0f, 1.0f), 0, 0))) > 0.999f);
  }
}

TEST_CASE("projection: points beyond every primitive's reach take the fallback direction", "[projection]") {
  const std::vector<PosedSegment> segs{{{0, 0, 0}, {1, 0, 0}, 0.1f, 1.0f}};
  const FieldProgram p = standinProgram(StandinKind::Convolution, 20.0f, segs);
  const glm::vec3 far(0.5f, 30.0f, 0.0f), near(0.5f, 0.2f, 0.0f);
  const std::vector<glm::vec3> in{far, near};
  std::vector<glm::vec3> out(2);
  const ProjectionStats st = projectOntoField(p, segs, in.data(), 2, out.data(), nullptr, {});
  CHECK(st.fallbacks == 1);
  CHECK(st.failures == 0);
  CHECK(std::abs(test::fieldAt(p, out[0])) < 1e-4f);
  CHECK(out[0].y > 0.0f);  // it came down from above
}
