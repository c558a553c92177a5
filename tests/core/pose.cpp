#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "core/rig/pose.h"
#include "core/rig/skinning.h"

using namespace animorph;

namespace {
// Two-bone arm along +X: root joint at the origin, elbow at x = 1, one mesh
// node with a skin; one vertex at x = 1.5 weighted 0.5 / 0.5.
Character twoBoneArm() {
  Character c;
  c.nodes.resize(3);
  c.nodes[0].name = "root";
  c.nodes[0].children = {1};
  c.nodes[1].name = "elbow";
  c.nodes[1].parent = 0;
  c.nodes[1].rest.translation = {1, 0, 0};
  c.nodes[2].name = "mesh";
  c.nodes[2].mesh = 0;
  c.nodes[2].skin = 0;
  c.roots = {0, 2};
  Skin s;
  s.joints = {0, 1};
  s.inverseBindMatrices = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0))};
  c.skins.push_back(s);
  Mesh m;
  m.positions = {{1.5f, 0, 0}};
  m.normals = {{0, 1, 0}};
  m.joints0 = {{0, 1, 0, 0}};
  m.weights0 = {{0.5f, 0.5f, 0, 0}};
  c.meshes.push_back(m);
  AnimationClip clip;
  clip.name = "bend";
  Channel ch;
  ch.node = 1;
  ch.path = ChannelPath::Rotation;
  ch.interpolation = Interpolation::Linear;
  ch.timesSec = {0.0f, 1.0f};
  glm::quat q90 = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
  ch.values = {{0, 0, 0, 1}, {q90.x, q90.y, q90.z, q90.w}};
  clip.channels.push_back(ch);
  clip.durationSec = 1.0f;
  c.clips.push_back(clip);
  return c;
}
}  // namespace

TEST_CASE("rest pose skinning returns the bind positions", "[rig]") {
  Character c = twoBoneArm();
  auto p = skinnedWorldPositions(c, nullptr, 0.0f);
  REQUIRE(p.size() == 1);
  CHECK(glm::length(p[0] - glm::vec3(1.5f, 0, 0)) < 1e-6f);
}

TEST_CASE("skinning at a hand-computed pose", "[rig]") {
  Character c = twoBoneArm();
  // At t = 1 the elbow has turned 90 degrees about Z: joint 1 carries the
  // vertex to (1, 0.5, 0); joint 0 leaves it at (1.5, 0, 0); the blend is the mean.
  auto p = skinnedWorldPositions(c, &c.clips[0], 1.0f);
  CHECK(glm::length(p[0] - glm::vec3(1.25f, 0.25f, 0)) < 1e-5f);
  // Halfway, the slerp gives 45 degrees.
  p = skinnedWorldPositions(c, &c.clips[0], 0.5f);
  float s = std::sqrt(0.5f) * 0.5f;
  CHECK(glm::length(p[0] - 0.5f * (glm::vec3(1.5f, 0, 0) + glm::vec3(1.0f + s, s, 0))) < 1e-5f);
}

TEST_CASE("step and cubic-spline channels", "[rig]") {
  Character c = twoBoneArm();
  Channel& ch = c.clips[0].channels[0];
  ch.path = ChannelPath::Translation;
  ch.interpolation = Interpolation::Step;
  ch.values = {{1, 0, 0, 0}, {3, 0, 0, 0}};
  auto locals = sampleLocalTransforms(c, &c.clips[0], 0.99f);
  CHECK(locals[1].translation.x == 1.0f);
  // Cubic spline with zero tangents: Hermite smoothstep between the values.
  ch.interpolation = Interpolation::CubicSpline;
  ch.values = {{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {3, 0, 0, 0}, {0, 0, 0, 0}};
  locals = sampleLocalTransforms(c, &c.clips[0], 0.5f);
  CHECK(locals[1].translation.x == Approx(2.0f));
  locals = sampleLocalTransforms(c, &c.clips[0], 0.25f);
  CHECK(locals[1].translation.x == Approx(1.0f + 2.0f * (3 * 0.0625f - 2 * 0.015625f)));
}

TEST_CASE("clip time loops or clamps", "[rig]") {
  AnimationClip clip;
  clip.durationSec = 2.0f;
  CHECK(clipTime(clip, 5.0, true) == Approx(1.0f));
  CHECK(clipTime(clip, -0.5, true) == Approx(1.5f));
  CHECK(clipTime(clip, 5.0, false) == Approx(2.0f));
}

TEST_CASE("transform decompose inverts compose", "[math]") {
  Transform t;
  t.translation = {1, -2, 3};
  t.rotation = glm::normalize(glm::quat(0.7f, 0.2f, -0.4f, 0.1f));
  t.scale = {2, 0.5f, 3};
  Transform d = decompose(t.matrix());
  CHECK(glm::length(d.translation - t.translation) < 1e-5f);
  CHECK(glm::length(d.scale - t.scale) < 1e-5f);
  CHECK(std::abs(glm::dot(d.rotation, t.rotation)) > 0.99999f);
}
