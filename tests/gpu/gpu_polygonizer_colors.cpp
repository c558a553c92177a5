// The GPU polygoniser's colour stream (docs/gpu-polygonizer.md, "Colour"): each vertex's colour from
// the colour pass against the CPU's SurfaceColorEvaluator at the same vertex (within the 1/255 of
// the 8-bit colour it is stored in), and a program without colours keeping the one tone.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>

#include "core/blobtree/compile.h"
#include "core/field/surface_color.h"
#include "demo/blob_creature.h"
#include "demo/dino_dragon.h"
#include "gpu/polygonizer/gpu_color_table.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "poly_constants.h"
#include "gpu/present/offscreen_target.h"
#include "gpu/render/scene_renderer.h"
#include "gpu_fixture.h"
#include "polygonizer_rig.h"
#include "util/blob_builders.h"
#include "util/morph_fixtures.h"
#include "util/test_skip.h"

using namespace animorph;
using namespace animorph::gpu;
using namespace animorph::test;

namespace {


// Every primitive of the subtree painted with one of four colours (so some ops are of one colour,
// others mixed).
void paintRandomly(BlobNode& n, std::mt19937& rng) {
  const glm::vec3 palette[4] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.2f, 0.9f}, {0.2f, 0.8f, 0.1f}, {0.95f, 0.9f, 0.3f}};
  if (paramIndex(n.type, "color") >= 0) n.vec3Param("color") = Vec3Track(palette[rng() % 4]);
  for (BlobNode& c : n.children) paintRandomly(c, rng);
}

Bounds cubeOf(float half) {
  Bounds b;
  b.add(glm::vec3(-half));
  b.add(glm::vec3(half));
  return b;
}

// The GPU's colours of program p against the CPU's at the GPU's own vertices.
struct ColorComparison {
  size_t vertices = 0, within = 0;  // vertices, those within 1/255 in every channel
  float largest = 0.0f;             // largest channel difference
};

// Colours a and b (one per vertex, same count) compared channel by channel.
ColorComparison compareColorSets(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
  ColorComparison c;
  c.vertices = a.size();
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    const glm::vec3 d = glm::abs(glm::vec3(a[i]) - glm::vec3(b[i]));
    const float m = std::max({d.r, d.g, d.b});
    c.largest = std::max(c.largest, m);
    if (m <= 1.0f / 255.0f + 1e-6f) ++c.within;
  }
  return c;
}

// The GPU's colours of field (its colour program, or program A) against the CPU's at the GPU's own
// vertices; gpuColors: the GPU's, when wanted.
ColorComparison compareColors(GpuPolygonizer& poly, const GpuField& field, const GpuPolygonizeSettings& s,
                              std::vector<glm::vec4>* gpuColors = nullptr) {
  auto st = poly.polygonize(field, s);
  INFO(st.error());
  REQUIRE(st.ok());
  REQUIRE(st->colors);
  auto mesh = poly.readBack();
  INFO(mesh.error());
  REQUIRE(mesh.ok());
  REQUIRE(mesh->colors.size() == mesh->positions.size());
  std::vector<glm::vec4> cpu(mesh->positions.size());
  const FieldProgram& colors = field.colors ? *field.colors : *field.a;
  SurfaceColorEvaluator().evaluate(colors, mesh->positions.data(), mesh->positions.size(), cpu.data(), 2);
  if (gpuColors) *gpuColors = mesh->colors;
  return compareColorSets(mesh->colors, cpu);
}
ColorComparison compareColors(GpuPolygonizer& poly, const FieldProgram& p, const GpuPolygonizeSettings& s) {
  return compareColors(poly, GpuField::single(p), s);
}

}  // namespace

TEST_CASE("GPU polygoniser: GPU and CPU colours of the same polygonisation agree within 1/255 (painted random trees, "
          "every op, the blob creature)",
          "[gpu][gpupoly][color]") {
  PolygonizerRig r;
  size_t vertices = 0, within = 0;
  float largest = 0.0f;
  std::set<int> ops;  // the op codes the programs used
  auto run = [&](const FieldProgram& p, const GpuPolygonizeSettings& s) {
    REQUIRE(programHasColors(p));
    for (const FieldOp& op : p.ops) ops.insert(int(op.code));
    const ColorComparison c = compareColors(*r.poly, p, s);
    INFO(c.vertices << " vertices, " << c.within << " within 1/255, largest difference " << c.largest);
    CHECK(c.vertices > 20);
    // Float rounding only (the kernels are the CPU's); a vertex on the seam of a union, where the
    // two operands' values tie within rounding, may take the other side's colour.
    CHECK(c.within * 1000 >= c.vertices * 998);
    vertices += c.vertices;
    within += c.within;
    largest = std::max(largest, c.largest);
  };
  // Seeded random trees over every operator, primitive class, skeleton kind and map kind the
  // generator makes (tests/util/blob_builders), each primitive painted.
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u}) {
    INFO("seed " << seed);
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    paintRandomly(tree.root, rng);
    FieldProgram p = compileFieldProgram(tree, 0.5);
    GpuPolygonizeSettings s;
    s.resolution = 40;
    s.bounds = cubeOf(1.2f);
    // Both pool variants of the colour pass (a uniform buffer: GPUs; storage: CPU devices, large programs).
    s.poolBuffer = seed % 2 ? GpuPolygonizeSettings::PoolBuffer::Uniform : GpuPolygonizeSettings::PoolBuffer::Storage;
    run(p, s);
    if (s.poolBuffer == GpuPolygonizeSettings::PoolBuffer::Uniform) {
      const GpuPolygonizeStats& st = r.poly->lastStats();
      CHECK(st.uniformPool);
    }
  }
  // Ops the generator makes rarely: an R-union node; a constant and capsules, and Remap (the morph's
  // scaled or bounded operands) in hand-built programs, each primitive its own colour.
  {
    BlobNode seg = segmentNode(3, glm::vec3(0.1f, -0.3f, 0), glm::vec3(0.2f, 0.3f, 0.1f), 0.3f);
    seg.vec3Param("color") = Vec3Track(glm::vec3(0.1f, 0.2f, 0.9f));
    BlobNode pt = pointNode(2, glm::vec3(-0.2f, 0, 0), 0.5f);
    pt.vec3Param("color") = Vec3Track(glm::vec3(0.9f, 0.1f, 0.1f));
    const FieldProgram runion = compileFieldProgram(treeOf(operatorNode(NodeType::RUnion, 1, {pt, seg}), 0.5f), 0.0);
    FieldProgram withConst;
    withConst.threshold = 0.5f;
    withConst.addConstant(0.2f);
    withConst.nextColor = glm::vec3(0.2f, 0.8f, 0.1f);
    withConst.addCapsule({glm::vec3(-0.3f, 0, 0), glm::vec3(0.3f, 0.1f, 0), 0.15f}, false, false);
    withConst.addOperator(OpCode::Sum, 2);
    withConst.finish();
    FieldProgram remapped;
    remapped.threshold = 0.5f;
    remapped.nextColor = glm::vec3(0.9f, 0.1f, 0.1f);
    remapped.addCapsule({glm::vec3(-0.3f, 0, 0), glm::vec3(0.3f, 0.1f, 0), 0.2f}, false, false);
    const float bounded[2] = {0.7f, 3.0f}, scaled[2] = {0.6f, 0.0f};
    remapped.addOperator(OpCode::Remap, 1, bounded, 2);
    remapped.nextColor = glm::vec3(0.1f, 0.2f, 0.9f);
    remapped.addConvolution(glm::vec3(0.0f, -0.3f, 0.0f), glm::vec3(0.1f, 0.3f, 0.1f), 0.15f, 12.0f, 1e-3f, false);
    remapped.addOperator(OpCode::Remap, 1, scaled, 2);
    remapped.addOperator(OpCode::Sum, 2);
    remapped.finish();
    for (const FieldProgram* p : std::initializer_list<const FieldProgram*>{&runion, &withConst, &remapped}) {
      GpuPolygonizeSettings s;
      s.resolution = 40;
      s.bounds = cubeOf(0.8f);
      run(*p, s);
    }
  }
  // The demo's blob creature (frames nesting its limbs), painted part by part.
  {
    BlobTree creature = makeBlobCreature();
    std::mt19937 rng(77);
    paintRandomly(creature.root, rng);
    FieldProgram p = compileFieldProgram(creature, 0.0);
    GpuPolygonizeSettings s;
    s.resolution = 64;
    run(p, s);
  }
  for (OpCode op : {OpCode::Prims, OpCode::Const, OpCode::Sum, OpCode::Max, OpCode::Min, OpCode::HyperBlend,
                    OpCode::Difference, OpCode::RUnion, OpCode::RIntersection, OpCode::BoundedBlend, OpCode::BeginMap,
                    OpCode::EndMap, OpCode::Remap}) {
    INFO("op " << int(op));
    CHECK(ops.count(int(op)) == 1);
  }
  std::printf("colours: %zu vertices, %zu within 1/255 of the CPU's, largest difference %g\n", size_t(vertices),
              size_t(within), double(largest));  // the figure only: the CHECKs above judge
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser: a program without colours has no colour stream (the one tone)", "[gpu][gpupoly][color]") {
  PolygonizerRig r;
  std::mt19937 rng(5);
  int id = 1;
  FieldProgram p = compileFieldProgram(treeOf(randomNode(rng, 3, id), 0.5f), 0.5);
  REQUIRE(!programHasColors(p));
  GpuPolygonizeSettings s;
  s.resolution = 32;
  s.bounds = cubeOf(1.2f);
  auto st = r.poly->polygonize(GpuField::single(p), s);
  REQUIRE(st.ok());
  CHECK_FALSE(st->colors);
  auto mesh = r.poly->readBack();
  REQUIRE(mesh.ok());
  CHECK(mesh->triangleCount() > 0);
  CHECK(mesh->colors.empty());
  // Colours turned off: none either, for a painted program.
  std::mt19937 paint(9);
  BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
  paintRandomly(tree.root, paint);
  FieldProgram painted = compileFieldProgram(tree, 0.5);
  REQUIRE(programHasColors(painted));
  s.colors = false;
  auto off = r.poly->polygonize(GpuField::single(painted), s);
  REQUIRE(off.ok());
  CHECK_FALSE(off->colors);
  auto offMesh = r.poly->readBack();
  REQUIRE(offMesh.ok());
  CHECK(offMesh->colors.empty());
  CHECK(r.ctx->validationErrorCount() == 0);
}

namespace {

// Point primitive `id` at centre with colour c (linear).
BlobNode colouredPoint(int id, const glm::vec3& centre, const glm::vec3& c) {
  BlobNode p = pointNode(id, centre, 0.7f);
  p.vec3Param("color") = Vec3Track(c);
  return p;
}

}  // namespace

TEST_CASE("GPU polygoniser: the GPU preview of a coloured BlobTree draws its vertices' colours, one without colours "
          "its one tone",
          "[gpu][gpupoly][color]") {
  PolygonizerRig r;
  auto target = OffscreenTarget::create(*r.ctx, 96, 96);
  REQUIRE(target.ok());
  auto renderer = SceneRenderer::create(*r.ctx, (*target)->renderPass());
  INFO(renderer.error());
  REQUIRE(renderer.ok());
  // A red point left, a blue one right, blended in the middle; the same shape without colours.
  BlobNode coloured = operatorNode(NodeType::Blend, 1,
                                   {colouredPoint(2, glm::vec3(-0.35f, 0, 0), glm::vec3(0.9f, 0.05f, 0.05f)),
                                    colouredPoint(3, glm::vec3(0.35f, 0, 0), glm::vec3(0.05f, 0.05f, 0.9f))});
  BlobNode plain = operatorNode(NodeType::Blend, 1,
                                {pointNode(2, glm::vec3(-0.35f, 0, 0), 0.7f), pointNode(3, glm::vec3(0.35f, 0, 0), 0.7f)});
  OrbitCamera cam;
  cam.target = glm::vec3(0.0f);
  cam.yawRad = 0.0f;
  cam.pitchRad = 0.0f;
  cam.distanceM = 3.0f;
  struct Counts {
    size_t covered = 0, reddish = 0, bluish = 0, grey = 0;
  };
  auto draw = [&](const BlobTree& tree) {
    FieldProgram p = compileFieldProgram(tree, 0.0);
    GpuPolygonizeSettings s;
    s.resolution = 32;
    Status recorded;
    Status submitted =
        r.ctx->submitImmediate([&](VkCommandBuffer cmd) { recorded = r.poly->record(cmd, 0, GpuField::single(p), s); });
    INFO(recorded.error() + submitted.error());
    REQUIRE(recorded.ok());
    REQUIRE(submitted.ok());
    Scene scene;
    scene.options.grid = false;
    scene.options.axisIndicator = false;
    scene.options.background = {0.0f, 0.0f, 0.0f, 1.0f};
    scene.generatedMeshes.push_back(r.poly->generatedMesh({0.62f, 0.62f, 0.62f, 1.0f}));
    Status drawn;
    Status rendered = (*target)->render(
        [&](VkCommandBuffer cmd) { drawn = (*renderer)->record(cmd, (*target)->serial(), {0, 0, 96, 96}, cam, scene); });
    REQUIRE(drawn.ok());
    REQUIRE(rendered.ok());
    const RgbaImage& img = (*target)->image();
    Counts c;
    for (uint32_t y = 0; y < 96; ++y)
      for (uint32_t x = 0; x < 96; ++x) {
        const glm::u8vec4 px = img.at(x, y);
        if (!differs(px, scene.options.background)) continue;
        ++c.covered;
        c.reddish += px.r > px.b + 40 && px.r > px.g + 40;
        c.bluish += px.b > px.r + 40 && px.b > px.g + 40;
        c.grey += std::abs(int(px.r) - int(px.b)) <= 3 && std::abs(int(px.r) - int(px.g)) <= 3;
      }
    return c;
  };
  const Counts col = draw(treeOf(coloured, 0.5f));
  INFO(col.covered << " covered: " << col.reddish << " reddish, " << col.bluish << " bluish, " << col.grey << " grey");
  CHECK(col.covered > 96 * 96 / 20);
  CHECK(col.reddish > col.covered / 5);
  CHECK(col.bluish > col.covered / 5);
  const Counts one = draw(treeOf(plain, 0.5f));
  INFO(one.covered << " covered: " << one.reddish << " reddish, " << one.bluish << " bluish, " << one.grey << " grey");
  CHECK(one.covered > 96 * 96 / 20);
  CHECK(one.grey == one.covered);  // the draw's grey tone, shaded
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser: a morph of two coloured stand-ins takes its colour program's colours (the CPU's within 1/255)",
          "[gpu][gpupoly][color]") {
  // The demo morph (creature -> gear, stand-ins coloured from the characters' materials): its
  // implicit stage's field, coloured by the colour program of split stand-in segments
  // (MorphImplicitField::colorProgram, GpuField::colors), at the start, middle and end of B..C.
  const MorphRuntime& rt = *test::demoMorph().runtime;
  REQUIRE(morphHasColors(rt));
  const MorphMarkers& k = rt.setup.markers;
  const double tb = rt.timeline.frameToSec(k.b), tc = rt.timeline.frameToSec(k.c);
  PolygonizerRig r;
  size_t vertices = 0, within = 0;
  float largest = 0.0f;
  glm::vec3 lo(1.0f), hi(0.0f);  // the colours' range over the three (the gear is bronze all over)
  for (double u : {0.0, 0.5, 1.0}) {
    INFO("u = " << u);
    const double t = tb + u * (tc - tb);
    MorphImplicitField f = morphImplicitField(rt, t, 64, u);
    REQUIRE(f.colorProgram);
    REQUIRE(programHasColors(*f.colorProgram));
    GpuField field = GpuField::single(f.program);
    field.colors = f.colorProgram.get();
    GpuPolygonizeSettings s;
    s.resolution = 64;
    s.bounds = f.bounds;
    auto st = r.poly->polygonize(field, s);
    INFO(st.error());
    REQUIRE(st.ok());
    REQUIRE(st->colors);
    CHECK(st->colorRegionLists);  // the colour program's own lists, though the field walks its whole program
    auto mesh = r.poly->readBack();
    REQUIRE(mesh.ok());
    REQUIRE(mesh->colors.size() == mesh->positions.size());
    REQUIRE(mesh->positions.size() > 100);
    std::vector<glm::vec4> cpu(mesh->positions.size());
    SurfaceColorEvaluator().evaluate(*f.colorProgram, mesh->positions.data(), mesh->positions.size(), cpu.data(), 2);
    size_t caseWithin = 0;
    for (size_t i = 0; i < cpu.size(); ++i) {
      const glm::vec3 d = glm::abs(glm::vec3(mesh->colors[i]) - glm::vec3(cpu[i]));
      const float m = std::max({d.r, d.g, d.b});
      largest = std::max(largest, m);
      caseWithin += m <= 1.0f / 255.0f + 1e-6f;
      lo = glm::min(lo, glm::vec3(mesh->colors[i]));
      hi = glm::max(hi, glm::vec3(mesh->colors[i]));
    }
    INFO(caseWithin << " of " << cpu.size() << " within 1/255");
    CHECK(caseWithin * 1000 >= cpu.size() * 998);
    vertices += cpu.size();
    within += caseWithin;
  }
  const glm::vec3 spread = hi - lo;
  CHECK(std::max({spread.r, spread.g, spread.b}) > 0.1f);  // coloured, not one tone
  std::printf("morph colours: %zu vertices, %zu within 1/255 of the CPU's, largest difference %g\n",
              size_t(vertices), size_t(within), double(largest));  // the figure only: the CHECKs above judge
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser: the colour pass walking per-region lists gives the whole walk's colours (painted random "
          "trees, the blob creature, the demo morph's colour program)",
          "[gpu][gpupoly][color]") {
  PolygonizerRig r;
  size_t vertices = 0, same = 0;
  // field with region programs on: its colours walking the lists and walking the whole program, each
  // against the CPU's, and against each other (the same mesh: the field passes walk the lists both times).
  auto run = [&](const GpuField& field, GpuPolygonizeSettings s) {
    s.regionPrograms = GpuPolygonizeSettings::RegionPrograms::On;
    s.colorRegionLists = true;
    std::vector<glm::vec4> lists, whole;
    const ColorComparison withLists = compareColors(*r.poly, field, s, &lists);
    CHECK(r.poly->lastStats().regionLists);
    CHECK(r.poly->lastStats().colorRegionLists);
    s.colorRegionLists = false;
    const ColorComparison withWhole = compareColors(*r.poly, field, s, &whole);
    CHECK_FALSE(r.poly->lastStats().colorRegionLists);
    REQUIRE(lists.size() == whole.size());
    const ColorComparison between = compareColorSets(lists, whole);
    INFO(withLists.vertices << " vertices; lists vs CPU " << withLists.within << ", whole vs CPU " << withWhole.within
                            << ", lists vs whole " << between.within << " within 1/255 (largest " << between.largest
                            << ")");
    CHECK(withLists.vertices > 20);
    CHECK(withLists.within * 1000 >= withLists.vertices * 998);
    CHECK(between.within * 1000 >= between.vertices * 998);
    vertices += between.vertices;
    same += between.within;
  };
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u}) {
    INFO("seed " << seed);
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    paintRandomly(tree.root, rng);
    const FieldProgram p = compileFieldProgram(tree, 0.5);
    GpuPolygonizeSettings s;
    s.resolution = 40;
    s.bounds = cubeOf(1.2f);
    run(GpuField::single(p), s);
  }
  {
    BlobTree creature = makeBlobCreature();
    std::mt19937 rng(77);
    paintRandomly(creature.root, rng);
    const FieldProgram p = compileFieldProgram(creature, 0.0);
    GpuPolygonizeSettings s;
    s.resolution = 64;
    run(GpuField::single(p), s);
  }
  {  // the demo morph half way through B..C: its own colour program's lists
    const MorphRuntime& rt = *test::demoMorph().runtime;
    const MorphMarkers& k = rt.setup.markers;
    const double t = rt.timeline.frameToSec(0.5 * (k.b + k.c));
    MorphImplicitField f = morphImplicitField(rt, t, 64, 0.5);
    REQUIRE(f.colorProgram);
    GpuField field = GpuField::single(f.program);
    field.colors = f.colorProgram.get();
    GpuPolygonizeSettings s;
    s.resolution = 64;
    s.bounds = f.bounds;
    run(field, s);
  }
  std::printf("colours walking region lists: %zu vertices, %zu within 1/255 of the whole walk's\n", vertices, same);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser: a coloured program too long for a whole colour walk on lavapipe gets GPU colours from the "
          "region lists (the animorphosis demo's dinosaur, the CPU's within 1/255)",
          "[gpu][gpupoly][color]") {
  PolygonizerRig r;
  const FieldProgram p = compileFieldProgram(makeDinosaur(), 0.5);
  REQUIRE(programHasColors(p));
  const uint64_t limit = GpuPolygonizer::loopLimit(r.ctx->properties());
  if (limit == 0) ANIMORPH_SKIP("the device has no loop limit (not lavapipe): nothing to exceed");
  // Before region lists the colour pass walked the whole program and refused one past this.
  INFO("whole colour walk ~" << colorWalkLoopEstimate(p) << " iterations, limit " << limit);
  REQUIRE(2 * colorWalkLoopEstimate(p) + 64 >= limit);
  GpuPolygonizeSettings s;
  s.resolution = 96;  // at 64^3 a block's list is too long for the colour pass's guard: no colours there
  const ColorComparison c = compareColors(*r.poly, p, s);
  const GpuPolygonizeStats& st = r.poly->lastStats();
  CHECK(st.regionLists);
  CHECK(st.colorRegionLists);
  INFO(c.vertices << " vertices, " << c.within << " within 1/255, largest difference " << c.largest);
  CHECK(c.vertices > 1000);
  CHECK(c.within * 1000 >= c.vertices * 998);
  // The whole walk is still refused (no colour stream, not a wrong one).
  s.colorRegionLists = false;
  auto whole = r.poly->polygonize(GpuField::single(p), s);
  INFO(whole.error());
  REQUIRE(whole.ok());
  CHECK_FALSE(whole->colors);
  std::printf("dinosaur colours from region lists: %zu vertices, %zu within 1/255 of the CPU's, largest difference "
              "%g\n", c.vertices, c.within, double(c.largest));
  CHECK(r.ctx->validationErrorCount() == 0);
}

namespace {
// n convolution segments summed in one op, each its own colour, around a ring of radius 0.5.
FieldProgram paintedRing(uint32_t n) {
  FieldProgram p;
  p.threshold = 0.5f;
  for (uint32_t i = 0; i < n; ++i) {
    const float a0 = 6.2831853f * float(i) / float(n), a1 = 6.2831853f * float(i + 1) / float(n);
    p.nextColor = glm::vec3(0.5f + 0.5f * std::cos(a0), 0.5f + 0.5f * std::sin(a0), 0.2f);
    p.addConvolution(0.5f * glm::vec3(std::cos(a0), std::sin(a0), 0.0f), 0.5f * glm::vec3(std::cos(a1), std::sin(a1), 0.0f),
                     0.08f, 12.0f, 1e-3f, i > 0);
  }
  p.finish();
  return p;
}
}  // namespace

TEST_CASE("GPU polygoniser: prewarm compiles the colour pass's pipeline and picks the frame's pool variant with the "
          "colour table counted",
          "[gpu][gpupoly][color]") {
  // A program whose pool alone fits the uniform buffer and with its colour table does not: the frame
  // reads it from a storage buffer, and prewarm must make that variant (not the uniform one).
  uint32_t n = 64;
  while (fieldProgramsShape(paintedRing(n + 64)).poolWords <= AM_POLY_UNIFORM_POOL_VEC4) n += 64;
  const FieldProgram p = paintedRing(n);
  const size_t poolWords = fieldProgramsShape(p).poolWords;
  INFO(n << " segments, pool " << poolWords << " words");
  REQUIRE(poolWords <= AM_POLY_UNIFORM_POOL_VEC4);
  REQUIRE(poolWords + p.ops.size() + p.primitiveCount() > AM_POLY_UNIFORM_POOL_VEC4);
  GpuPolygonizeSettings s;
  s.resolution = 32;
  const GpuField field = GpuField::single(p);
  {
    PolygonizerRig r;
    CHECK_FALSE(r.poly->ready(field, s));
    r.poly->prewarm(field, s);
    REQUIRE(r.poly->waitForCompilation(300.0));
    CHECK(r.poly->ready(field, s));
    CHECK(r.poly->variantCount() == 1);
    GpuPolygonizeStats st;
    (void)r.polygonizeAndRead(field, s, nullptr, st);
    CHECK(st.colors);
    CHECK_FALSE(st.regionLists);  // whole programs: the pool's size alone picks the buffer
    CHECK_FALSE(st.uniformPool);
    CHECK_FALSE(st.colorPipelineMadeInRecord);  // prewarm made it
    CHECK(r.poly->variantCount() == 1);          // the prewarmed variant was the frame's
    CHECK(r.ctx->validationErrorCount() == 0);
  }
  {  // without prewarm the first coloured frame makes it, the next does not
    PolygonizerRig r;
    GpuPolygonizeStats st;
    (void)r.polygonizeAndRead(field, s, nullptr, st);
    CHECK(st.colors);
    CHECK(st.colorPipelineMadeInRecord);
    (void)r.polygonizeAndRead(field, s, nullptr, st);
    CHECK_FALSE(st.colorPipelineMadeInRecord);
    CHECK(r.ctx->validationErrorCount() == 0);
  }
}
