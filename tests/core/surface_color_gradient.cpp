// The CPU polygoniser's normals and colours in one walk (SurfaceColorEvaluator::
// evaluateActiveWithGradient, docs/blobtree.md "Colour"): its field and gradient must be the field
// evaluator's bit for bit over the same points, equal to it (+0 and -0 alike: a zero gradient's
// sign depends on the run) over other runs of the same points, and its colours the colour walk's
// (evaluateActive) within float rounding; a polygonisation with colours must have the normals of
// one without, bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "core/animorphosis/evaluate_generic.h"
#include "core/blobtree/compile.h"
#include "core/field/surface_color.h"
#include "core/poly/polygonizer.h"
#include "core/project/animorphosis_project.h"
#include "demo/animorphosis_demo.h"
#include "demo/blob_creature.h"
#include "util/blob_builders.h"

using namespace animorph;

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every primitive of the subtree painted with one of four colours (so some ops are of one colour,
// others mixed; the clay tone among them, the colour of constants).
void paintFromPalette(BlobNode& n, std::mt19937& rng) {
  const glm::vec3 palette[4] = {{1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f}, kDefaultBlobColor};
  if (paramIndex(n.type, "color") >= 0) n.vec3Param("color") = Vec3Track(palette[rng() % 4]);
  for (BlobNode& c : n.children) paintFromPalette(c, rng);
}

// A seeded random tree of every node type (operators, maps, meta-primitives), painted; nullopt
// when it has no bounded surface.
std::optional<FieldProgram> randomPaintedProgram(unsigned seed) {
  std::mt19937 rng(seed);
  int nextId = 1;
  BlobTree t = test::treeOf(test::randomNode(rng, 4, nextId), 0.5f);
  paintFromPalette(t.root, rng);
  FieldProgram prog = compileFieldProgram(t, 0.0);
  if (prog.unbounded() || prog.tightBounds().empty()) return std::nullopt;
  return prog;
}

FieldProgram demoProgramHalfway() {
  auto project = makeAnimorphosisDemoProject();
  REQUIRE(project.ok());
  auto c = projectGenericTree(*project);
  REQUIRE(c.ok());
  return compileGeneric(*c, animorphosisTiming(*project), 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec));
}

struct WalkAgreement {
  size_t points = 0, fieldDiffers = 0, gradientDiffers = 0;  // bits, against the evaluator on the same run
  size_t unequalInPieces = 0;  // field or gradient !=, against the evaluator on pieces of 8 points
  float color = 0.0f;  // largest channel difference against the colour walk
};

// The points in runs of 100 consecutive ones (polygonised vertices come block by block: compact
// runs), each run with the program specialised to its box (every other run: the whole program).
// The combined walk over the whole run against the field evaluator over the whole run and over
// pieces of 8 points (as the polygoniser's sub-blocks have them), and the colour walk over the
// whole run.
WalkAgreement compareWalks(const FieldProgram& prog, const std::vector<glm::vec3>& points) {
  const ColorProgram cp(prog);
  SurfaceColorEvaluator combined, colorWalk;
  FieldEvaluator fe;
  ActiveProgram active;
  std::vector<uint32_t> reach;
  WalkAgreement a;
  constexpr size_t kRunPoints = 100;
  for (size_t b = 0, run = 0; b < points.size(); b += kRunPoints, ++run) {
    const size_t count = std::min(kRunPoints, points.size() - b);
    const int n = int(count);
    std::vector<float> x(count), y(count), z(count);
    Bounds box;
    for (int i = 0; i < n; ++i) {
      const glm::vec3& p = points[b + size_t(i)];
      x[size_t(i)] = p.x;
      y[size_t(i)] = p.y;
      z[size_t(i)] = p.z;
      box.add(p);
    }
    if (run % 2 == 0) {
      prog.primitivesReaching(box, reach);
      prog.specialise(reach, active);
    } else {
      prog.specialiseAll(active);
    }
    std::vector<float> f(count), gx(count), gy(count), gz(count), fp(count), gxp(count), gyp(count), gzp(count);
    fe.evaluate(prog, active, x.data(), y.data(), z.data(), n, f.data(), gx.data(), gy.data(), gz.data());
    for (int p = 0; p < n; p += 8) {
      const int m = std::min(8, n - p);
      fe.evaluate(prog, active, &x[size_t(p)], &y[size_t(p)], &z[size_t(p)], m, &fp[size_t(p)], &gxp[size_t(p)],
                  &gyp[size_t(p)], &gzp[size_t(p)]);
    }
    std::vector<glm::vec4> want(count), got(count);
    colorWalk.evaluateActive(cp, active, x.data(), y.data(), z.data(), n, want.data());
    std::vector<float> f2(count), gx2(count), gy2(count), gz2(count);
    combined.evaluateActiveWithGradient(cp, active, x.data(), y.data(), z.data(), n, got.data(), f2.data(),
                                        gx2.data(), gy2.data(), gz2.data());
    for (size_t i = 0; i < count; ++i) {
      a.fieldDiffers += !sameBits(f[i], f2[i]);
      a.gradientDiffers += !(sameBits(gx[i], gx2[i]) && sameBits(gy[i], gy2[i]) && sameBits(gz[i], gz2[i]));
      a.unequalInPieces += !(fp[i] == f2[i] && gxp[i] == gx2[i] && gyp[i] == gy2[i] && gzp[i] == gz2[i]);
      const glm::vec4 d = glm::abs(got[i] - want[i]);
      a.color = std::max({a.color, d.r, d.g, d.b, d.a});
    }
    a.points += count;
  }
  return a;
}

void checkWalks(const WalkAgreement& a) {
  INFO(a.points << " points: field differs at " << a.fieldDiffers << ", gradient at " << a.gradientDiffers
                << ", unequal to the evaluator's in pieces of 8 at " << a.unequalInPieces
                << "; largest colour difference " << a.color);
  CHECK(a.points > 0);
  CHECK(a.fieldDiffers == 0);
  CHECK(a.gradientDiffers == 0);
  CHECK(a.unequalInPieces == 0);
  CHECK(a.color <= 1e-5f);
}

// The vertices of prog polygonised at `resolution` without colours, in the mesh's order.
std::vector<glm::vec3> surfacePoints(const FieldProgram& prog, int resolution) {
  PolygonizeSettings ps;
  ps.resolution = resolution;
  ps.threads = 1;
  auto r = polygonize(prog, ps);
  REQUIRE(r.ok());
  return r->mesh.positions;
}

// Seeded points scattered over the program's bounds (inside, outside, far from the surface),
// sorted along x so runs are compact in one direction only.
std::vector<glm::vec3> scatteredPoints(const FieldProgram& prog, unsigned seed, size_t count) {
  std::mt19937 rng(seed);
  const Bounds& b = prog.tightBounds();
  const glm::vec3 lo = b.min - 0.2f * b.size(), hi = b.max + 0.2f * b.size();
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> out(count);
  for (glm::vec3& p : out) p = lo + glm::vec3(u(rng), u(rng), u(rng)) * (hi - lo);
  std::sort(out.begin(), out.end(), [](const glm::vec3& p, const glm::vec3& q) { return p.x < q.x; });
  return out;
}

// Polygonised with and without colours: the same vertices and normals, bit for bit.
void checkPolygonizerNormals(const FieldProgram& prog, int resolution) {
  PolygonizeSettings ps;
  ps.resolution = resolution;
  ps.threads = 2;
  auto plain = polygonize(prog, ps);
  ps.colors = true;
  auto colored = polygonize(prog, ps);
  REQUIRE(plain.ok());
  REQUIRE(colored.ok());
  const TriangleMesh &a = plain->mesh, &b = colored->mesh;
  REQUIRE(a.positions.size() == b.positions.size());
  REQUIRE(a.normals.size() == b.normals.size());
  REQUIRE(b.colors.size() == b.positions.size());
  size_t positionDiffers = 0, normalDiffers = 0;
  for (size_t i = 0; i < a.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      positionDiffers += !sameBits(a.positions[i][k], b.positions[i][k]);
      normalDiffers += !sameBits(a.normals[i][k], b.normals[i][k]);
    }
  }
  INFO(a.positions.size() << " vertices at " << resolution << "^3: positions differ in " << positionDiffers
                          << " components, normals in " << normalDiffers);
  CHECK(positionDiffers == 0);
  CHECK(normalDiffers == 0);
  CHECK(a.indices == b.indices);
}

// A program of every primitive class and the operators the BlobTree compiler does not make (a
// stand-in core's remap over a sum of a capsule, a convolution segment and a point), in three
// colours.
FieldProgram remappedClasses() {
  FieldProgram p;
  p.threshold = 0.5f;
  p.nextColor = {1.0f, 0.0f, 0.0f};
  p.addCapsule(CapsulePrimitive{{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, 0.2f}, false, false);
  p.nextColor = {0.0f, 0.0f, 1.0f};
  p.addConvolution({0.0f, -0.4f, 0.0f}, {0.0f, 0.4f, 0.1f}, 0.25f, 8.0f, 1e-3f, false);
  p.nextColor = {0.0f, 1.0f, 0.0f};
  SkeletalPrimitive point;
  point.skeleton.kind = SkeletonKind::Point;
  point.skeleton.p0 = {0.3f, 0.3f, 0.0f};
  point.radius = 0.5f;
  point.intensity = 1.0f;
  point.stiffness = 2.0f;
  p.addSkeletal(point, false, false);
  p.addOperator(OpCode::Sum, 3);
  const float prm[2] = {0.8f, 2.0f};
  p.addOperator(OpCode::Remap, 1, prm, 2);
  p.finish();
  return p;
}

}  // namespace

TEST_CASE("colour: the combined walk gives the field evaluator's field and gradient bit for bit and the colour "
          "walk's colours (seeded random painted trees of every node type, a remap, the demo's C(t))",
          "[color]") {
  SECTION("seeded random painted trees: at their surface and scattered around it") {
    int compared = 0;
    for (unsigned seed = 1; seed <= 24; ++seed) {
      const std::optional<FieldProgram> prog = randomPaintedProgram(seed);
      if (!prog) continue;
      INFO("seed " << seed);
      std::vector<glm::vec3> points = surfacePoints(*prog, 32);
      const std::vector<glm::vec3> scattered = scatteredPoints(*prog, seed, 400);
      points.insert(points.end(), scattered.begin(), scattered.end());
      checkWalks(compareWalks(*prog, points));
      ++compared;
    }
    CHECK(compared >= 12);
  }
  SECTION("capsule, convolution segment and point summed under a remap") {
    const FieldProgram prog = remappedClasses();
    std::vector<glm::vec3> points = surfacePoints(prog, 40);
    CHECK(points.size() > 500);
    const std::vector<glm::vec3> scattered = scatteredPoints(prog, 7, 600);
    points.insert(points.end(), scattered.begin(), scattered.end());
    checkWalks(compareWalks(prog, points));
  }
  SECTION("the animorphosis demo's C(t) halfway (22k mapped primitives, both creatures' colours blending)") {
    const FieldProgram prog = demoProgramHalfway();
    const std::vector<glm::vec3> points = surfacePoints(prog, 48);
    CHECK(points.size() > 1000);
    checkWalks(compareWalks(prog, points));
  }
}

TEST_CASE("colour: a polygonisation with colours has the normals of one without, bit for bit (the demo's C(t), the "
          "blob creature, a remap, seeded random painted trees)",
          "[color]") {
  SECTION("the animorphosis demo's C(t) halfway at 64^3") { checkPolygonizerNormals(demoProgramHalfway(), 64); }
  SECTION("the blob creature, mid-stride, painted") {
    BlobTree t = makeBlobCreature();
    std::mt19937 rng(5);
    paintFromPalette(t.root, rng);
    checkPolygonizerNormals(compileFieldProgram(t, 0.7), 64);
  }
  SECTION("a remap over three primitive classes") { checkPolygonizerNormals(remappedClasses(), 48); }
  SECTION("seeded random painted trees") {
    int compared = 0;
    for (unsigned seed = 1; seed <= 16; ++seed) {
      const std::optional<FieldProgram> prog = randomPaintedProgram(seed);
      if (!prog) continue;
      INFO("seed " << seed);
      checkPolygonizerNormals(*prog, 40);
      ++compared;
    }
    CHECK(compared >= 8);
  }
}
