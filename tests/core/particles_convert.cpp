#include <catch2/catch.hpp>

#include <cmath>

#include "core/blobtree/compile.h"
#include "demo/statue.h"
#include "core/particles/convert_to_particles.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "util/manifold_checks.h"

using namespace animorph;
using animorph::test::polygonisedVolume;

namespace {

void checkVolume(int count, int res) {
  BlobTree statue = makeStatue();
  FieldProgram shape = compileFieldProgram(statue, 0.0);
  ConvertToParticlesSettings s;
  s.count = count;
  auto conv = convertToParticles(shape, s);
  REQUIRE(conv);
  const auto& rep = conv->report;
  CHECK(rep.particles >= size_t(count));
  CHECK(double(rep.particles) <= 1.01 * count);
  CHECK(conv->tree.root.children.size() == rep.particles);
  // A particle alone still shows (its peak is above the threshold).
  CHECK(rep.intensity > 1.0f);
  FieldProgram particles = compileFieldProgram(conv->tree, 0.0);
  Bounds box = shape.tightBounds();
  box.add(particles.tightBounds());
  box.min -= glm::vec3(0.05f);
  box.max += glm::vec3(0.05f);
  double v0 = polygonisedVolume(shape, box, res);
  double v1 = polygonisedVolume(particles, box, res);
  INFO(count << " particles: statue " << v0 << " m^3, particles " << v1 << " m^3");
  CHECK(std::abs(v1 - v0) <= 0.02 * v0);
}

}  // namespace

TEST_CASE("particles: a shape converted to particles keeps its volume within 2 %", "[particles][convert]") {
  checkVolume(4000, 96);
}

TEST_CASE("particles: 40,000 particles keep the volume within 2 % at 128^3", "[particles][convert]") {
  checkVolume(40000, 128);
}

TEST_CASE("particles: converting gives the count asked within 1 % above", "[particles][convert]") {
  // 300 used to give 341: the spacing (and the lattice's phase) is now searched.
  FieldProgram shape = compileFieldProgram(makeStatue(), 0.0);
  for (int count : {100, 300, 777, 3000, 10000}) {
    ConvertToParticlesSettings s;
    s.count = count;
    auto conv = convertToParticles(shape, s);
    REQUIRE(conv);
    INFO(count << " asked, " << conv->report.particles << " made");
    CHECK(conv->report.particles >= size_t(count));
    CHECK(double(conv->report.particles) <= 1.01 * count);
    CHECK(conv->tree.root.children.size() == conv->report.particles);
    CHECK(conv->report.intensity > 1.0f);
  }
}

TEST_CASE("particles: converting refuses bad input", "[particles][convert]") {
  FieldProgram shape = compileFieldProgram(makeStatue(), 0.0);
  ConvertToParticlesSettings s;
  s.count = 0;
  auto r = convertToParticles(shape, s);
  REQUIRE_FALSE(r);
  CHECK(r.error().find("count") != std::string::npos);
  FieldProgram empty;
  empty.finish();
  CHECK_FALSE(convertToParticles(empty, ConvertToParticlesSettings{}));
}

TEST_CASE("particles: per-sub-block primitive lists give the same mesh as dense evaluation", "[particles][convert]") {
  ConvertToParticlesSettings s;
  s.count = 1500;
  auto conv = convertToParticles(compileFieldProgram(makeStatue(), 0.0), s);
  REQUIRE(conv);
  FieldProgram program = compileFieldProgram(conv->tree, 0.0);
  PolygonizeSettings ps;
  ps.resolution = 48;
  auto culled = polygonize(program, ps);  // points: no lists, sub-block runs
  ps.subBlockListsForSkeletal = true;
  auto lists = polygonize(program, ps);  // per-sub-block lists, as before
  ps.subBlockListsForSkeletal = false;
  ps.subBlockLists = false;
  auto perBlock = polygonize(program, ps);
  ps.culling = false;
  auto dense = polygonize(program, ps);
  REQUIRE(culled);
  REQUIRE(dense);
  CHECK(culled->mesh.triangleCount() > 1000);
  CHECK(culled->mesh.positions == dense->mesh.positions);
  CHECK(culled->mesh.indices == dense->mesh.indices);
  CHECK(culled->stats.orphanVertices == 0);
  REQUIRE(perBlock);
  REQUIRE(lists);
  CHECK(perBlock->mesh == culled->mesh);  // normals too
  CHECK(lists->mesh == culled->mesh);
  // The lists give the evaluator fewer candidates (it skips the others itself, run by run).
  CHECK(lists->stats.primitiveEvaluations * 2 < perBlock->stats.primitiveEvaluations);
  // Surface-bound: far fewer (point, primitive) pairs than points x primitives.
  CHECK(culled->stats.primitiveEvaluations * 20 < dense->stats.primitiveEvaluations);
}
