#include <catch2/catch.hpp>

#include <cmath>

#include "blobtree/compile.h"
#include "demo/statue.h"
#include "particles/convert_to_particles.h"
#include "poly/mesh_checks.h"
#include "poly/polygonizer.h"

using namespace animorph;

namespace {

double polygonisedVolume(const FieldProgram& program, const Bounds& box, int res) {
  PolygonizeSettings ps;
  ps.resolution = res;
  ps.bounds = box;
  auto r = polygonize(program, ps);
  REQUIRE(r);
  REQUIRE(analyzeMesh(r->mesh).watertight());
  return meshVolume(r->mesh);
}

void checkVolume(int count, int res) {
  BlobTree statue = makeStatue();
  FieldProgram shape = compileFieldProgram(statue, 0.0);
  ConvertToParticlesSettings s;
  s.count = count;
  auto conv = convertToParticles(shape, s);
  REQUIRE(conv);
  const auto& rep = conv->report;
  CHECK(std::abs(double(rep.particles) - count) <= 0.05 * count);
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
