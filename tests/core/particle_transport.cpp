// Re-forming into another shape (particles/particle_transport.h): the assignment of particles to a
// second shape's places.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <tuple>

#include "core/blobtree/compile.h"
#include "core/particles/particle_animorphosis.h"
#include "core/particles/particle_transport.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;

namespace {

std::vector<glm::vec3> randomBox(size_t n, unsigned seed, glm::vec3 lo, glm::vec3 hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> v(n);
  for (auto& p : v) p = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
  return v;
}

bool isPermutation(std::vector<int> t) {
  std::sort(t.begin(), t.end());
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i] != int(i)) return false;
  return true;
}

// Pairs of particles whose exchange of places would shorten the sum of squared distances.
size_t improvingPairs(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, const std::vector<int>& t) {
  auto d2 = [](glm::vec3 x, glm::vec3 y) { return glm::dot(x - y, x - y); };
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = i + 1; j < a.size(); ++j) {
      const float now = d2(a[i], b[size_t(t[i])]) + d2(a[j], b[size_t(t[j])]);
      const float swapped = d2(a[i], b[size_t(t[j])]) + d2(a[j], b[size_t(t[i])]);
      if (swapped < now * (1.0f - 1e-4f)) ++n;
    }
  return n;
}

}  // namespace

TEST_CASE("particles are assigned to a second shape's places without exchanges left that shorten the paths",
          "[particles][transport]") {
  // A tall box of particles re-forms into a flat slab beside it.
  const auto from = randomBox(300, 1, {-0.2f, 0.0f, -0.2f}, {0.2f, 1.5f, 0.2f});
  const auto to = randomBox(300, 2, {1.0f, 0.0f, -0.6f}, {2.2f, 0.2f, 0.6f});
  ParticleTransportSettings s;
  s.neighbours = 299;  // every pair is tried
  auto r = assignParticles(from, to, s);
  REQUIRE(r);
  CHECK(isPermutation(r->target));
  CHECK(r->report.cost <= r->report.greedyCost);
  CHECK(r->report.cost == Approx(transportCost(from, to, r->target)));
  CHECK(r->report.exchanges > 0);
  CHECK(improvingPairs(from, to, r->target) == 0);
  // The greedy start alone leaves such pairs: the exchanges did work.
  std::vector<int> identity(from.size());
  for (size_t i = 0; i < identity.size(); ++i) identity[i] = int(i);
  CHECK(improvingPairs(from, to, identity) > 100);

  // With the default neighbourhood, the result is close to the all-pairs one.
  auto local = assignParticles(from, to);
  REQUIRE(local);
  CHECK(isPermutation(local->target));
  CHECK(local->report.cost <= r->report.cost * 1.02);
}

TEST_CASE("a translated copy of the particles is reached by the translation", "[particles][transport]") {
  const auto from = randomBox(2000, 3, {0.0f, 0.0f, 0.0f}, {1.0f, 2.0f, 0.5f});
  std::vector<glm::vec3> to = from;
  const glm::vec3 shift(3.0f, 0.5f, -1.0f);
  for (auto& p : to) p += shift;
  std::shuffle(to.begin(), to.end(), std::mt19937(4));
  auto r = assignParticles(from, to);
  REQUIRE(r);
  CHECK(isPermutation(r->target));
  const double optimal = double(from.size()) * double(glm::dot(shift, shift));
  CHECK(r->report.cost == Approx(optimal).epsilon(0.01));
  size_t exact = 0;
  for (size_t i = 0; i < from.size(); ++i)
    if (glm::length(to[size_t(r->target[i])] - (from[i] + shift)) < 1e-5f) ++exact;
  CHECK(exact >= from.size() * 95 / 100);
}

TEST_CASE("particle transport refuses sets of different sizes, reformed particles rest at their places",
          "[particles][transport]") {
  CHECK_FALSE(assignParticles(std::vector<glm::vec3>(3), std::vector<glm::vec3>(4)));
  std::vector<BlobNode> pts;
  for (int i = 0; i < 3; ++i) pts.push_back(pointNode(2 + i, glm::vec3(float(i), 0.0f, 0.0f), 0.1f, 2.0f));
  const BlobTree tree = treeOf(operatorNode(NodeType::Blend, 1, std::move(pts)), 1.0f);
  const std::vector<glm::vec3> places = {{0.0f, 5.0f, 0.0f}, {1.0f, 5.0f, 0.0f}, {2.0f, 5.0f, 0.0f}};
  auto moved = reformedParticles(tree, places, {2, 0, 1});
  REQUIRE(moved);
  CHECK(moved->root.children[0].vec3Param("center").evaluate(0.0) == places[2]);
  CHECK(moved->root.children[1].vec3Param("center").evaluate(7.0) == places[0]);
  CHECK_FALSE(reformedParticles(tree, places, {0, 1}));
}

TEST_CASE("particles of one shape re-form into another: the gathering ends in the second shape",
          "[particles][transport]") {
  // A tall capsule converted to particles re-forms into a flat, wide one beside it.
  const BlobTree tall = treeOf(segmentNode(1, {0.0f, 0.2f, 0.0f}, {0.0f, 1.2f, 0.0f}, 0.35f), 0.5f);
  const BlobTree wide = treeOf(segmentNode(1, {0.8f, 0.25f, 0.0f}, {2.2f, 0.25f, 0.0f}, 0.35f), 0.5f);
  ConvertToParticlesSettings cs;
  cs.count = 400;
  auto particles = convertToParticles(compileFieldProgram(tall, 0.0), cs);
  REQUIRE(particles);
  const size_t n = particles->report.particles;
  ParticleTransportReport report;
  const FieldProgram wideField = compileFieldProgram(wide, 0.0);
  auto reformed = reformIntoShape(particles->tree, 0.0, wideField, cs, {}, &report);
  REQUIRE(reformed);
  CHECK(report.cost <= report.greedyCost);
  // Every particle rests inside the second shape, on a place of its own.
  TreeParticles at = treeParticles(*reformed, 0.0);
  REQUIRE(at.set.position.size() == n);
  FieldEvaluator ev;
  size_t inside = 0;
  for (const glm::vec3& p : at.set.position)
    if (ev.evaluatePoint(wideField, p) >= 0.0f) ++inside;
  CHECK(inside == n);
  std::vector<glm::vec3> sorted = at.set.position;
  std::sort(sorted.begin(), sorted.end(), [](glm::vec3 a, glm::vec3 b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());

  // The animorphosis explodes the tall shape and gathers into the wide one.
  ParticleAnimorphosisSettings as;
  as.explosion.durationSec = 1.0;
  as.explosion.rateHz = 60.0;
  as.explosion.forces.explosion.centre = {0.0f, 0.7f, 0.0f};
  as.vortex.forces.explosion.enabled = false;
  as.vortex.forces.vortex.enabled = true;
  as.gatheringRest = *reformed;
  auto anim = makeParticleAnimorphosis(particles->tree, as);
  REQUIRE(anim);
  TreeParticles end = treeParticles(anim->gathering, anim->endSec);
  TreeParticles start = treeParticles(anim->exploding, anim->startSec);
  float far = 0.0f;
  for (size_t i = 0; i < n; ++i) far = std::max(far, glm::length(end.set.position[i] - at.set.position[i]));
  CHECK(far < 0.02f);  // within the bake tolerance (and a little)
  CHECK(glm::length(start.set.position[0] - treeParticles(particles->tree, 0.0).set.position[0]) < 1e-4f);
}
