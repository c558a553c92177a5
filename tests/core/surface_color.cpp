// BlobTree colour (docs/blobtree.md, "Colour"): the primitives' colour parameter, its blend at a
// point of the surface weighted by the primitives' field contributions, the operators' rules, the
// JSON default for files without colours, the polygonised meshes' vertex colours, and the
// animorphosis' interpolation of colours (a null partner fading its colour with its shape).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/generic_tree.h"
#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "core/field/surface_color.h"
#include "core/particles/convert_to_particles.h"
#include "core/poly/polygonizer.h"
#include "core/project/animorphosis_project.h"
#include "demo/animorphosis_demo.h"
#include "demo/blob_creature.h"
#include "util/blob_builders.h"

using namespace animorph;
using Catch::Matchers::Contains;

namespace {

const glm::vec3 kRed{1.0f, 0.0f, 0.0f}, kBlue{0.0f, 0.0f, 1.0f}, kGreen{0.0f, 1.0f, 0.0f};

BlobNode coloredPoint(int id, const glm::vec3& centre, const glm::vec3& color, float radius = 1.0f) {
  BlobNode p = makeBlobNode(NodeType::Point, id);
  p.vec3Param("center") = Vec3Track(centre);
  p.floatParam("radius") = FloatTrack(radius);
  p.vec3Param("color") = Vec3Track(color);
  return p;
}

BlobTree twoPoints(NodeType op, const glm::vec3& ca, const glm::vec3& cb) {
  BlobTree t;
  t.threshold = FloatTrack(0.5f);
  t.root = makeBlobNode(op, 1, "root");
  t.root.children.push_back(coloredPoint(2, glm::vec3(0.0f), ca));
  t.root.children.push_back(coloredPoint(3, glm::vec3(1.0f, 0.0f, 0.0f), cb));
  return t;
}

void checkNear(const glm::vec3& got, const glm::vec3& want, float tol = 1e-5f) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y << ", "
               << want.z << ")");
  CHECK(glm::all(glm::lessThanEqual(glm::abs(got - want), glm::vec3(tol))));
}

// Every primitive of the subtree painted with one of three colours (so some ops are of one colour,
// others mixed).
void paintRandomly(BlobNode& n, std::mt19937& rng) {
  const glm::vec3 palette[3] = {kRed, kBlue, kGreen};
  if (paramIndex(n.type, "color") >= 0) n.vec3Param("color") = Vec3Track(palette[rng() % 3]);
  for (BlobNode& c : n.children) paintRandomly(c, rng);
}

float largestChannel(const glm::vec4& d) {
  return std::max({std::abs(d.r), std::abs(d.g), std::abs(d.b), std::abs(d.a)});
}

// The polygoniser's vertex colours (each block's own programs) against two references at the same
// vertices: the run-sorted evaluate() at every vertex, and the unrestricted walk over the whole
// program at every stride-th. And at those: the whole program's field against the program
// specialised to a cell-sized box around the vertex (the reach bounds are safe there).
struct ColorAgreement {
  float vsRuns = 0.0f, vsFull = 0.0f, field = 0.0f;
  size_t vertices = 0, sampled = 0;
};
ColorAgreement compareBlockColors(const FieldProgram& prog, int resolution, size_t stride) {
  PolygonizeSettings ps;
  ps.resolution = resolution;
  ps.threads = 2;
  ps.colors = true;
  auto r = polygonize(prog, ps);
  REQUIRE(r.ok());
  const TriangleMesh& m = r->mesh;
  REQUIRE(m.colors.size() == m.positions.size());
  ColorAgreement a;
  a.vertices = m.positions.size();
  std::vector<glm::vec4> runs(m.positions.size());
  SurfaceColorEvaluator ev;
  ev.evaluate(prog, m.positions.data(), m.positions.size(), runs.data(), 2);
  std::vector<glm::vec3> sample;
  std::vector<glm::vec4> sampleBlock;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    a.vsRuns = std::max(a.vsRuns, largestChannel(m.colors[i] - runs[i]));
    if (i % stride == 0) {
      sample.push_back(m.positions[i]);
      sampleBlock.push_back(m.colors[i]);
    }
  }
  std::vector<glm::vec4> full(sample.size());
  ev.evaluateFull(prog, sample.data(), sample.size(), full.data());
  FieldEvaluator fe;
  std::vector<uint32_t> reach;
  ActiveProgram active;
  const glm::vec3 h(r->stats.cellSize);
  for (size_t i = 0; i < sample.size(); ++i) {
    a.vsFull = std::max(a.vsFull, largestChannel(sampleBlock[i] - full[i]));
    Bounds box;
    box.add(sample[i] - h);
    box.add(sample[i] + h);
    prog.primitivesReaching(box, reach);
    prog.specialise(reach, active);
    float f = 0.0f;
    fe.evaluate(prog, active, &sample[i].x, &sample[i].y, &sample[i].z, 1, &f);
    a.field = std::max(a.field, std::abs(f - fe.evaluatePoint(prog, sample[i])));
  }
  a.sampled = sample.size();
  return a;
}

// Colours equal within an 8-bit colour's step (what differs is float rounding only,
// field/surface_color.h); the field within float rounding of its threshold.
void checkAgreement(const ColorAgreement& a, const FieldProgram& prog) {
  INFO(a.vertices << " vertices (" << a.sampled << " against the whole walk): largest colour difference "
                  << a.vsRuns << " against the runs, " << a.vsFull << " against the whole walk; field " << a.field);
  CHECK(a.vsRuns <= 1.0f / 255.0f);
  CHECK(a.vsFull <= 1.0f / 255.0f);
  CHECK(a.field <= 1e-5f * std::max(1.0f, prog.threshold));
}

}  // namespace

TEST_CASE("colour: the polygoniser colours each vertex with its block's program as the whole walk does "
          "(the animorphosis demo's C(t) at two times, the blob creature, seeded random trees)",
          "[color]") {
  SECTION("the animorphosis demo's C(t): a quarter and halfway (both creatures' colours blending, 22k primitives)") {
    auto project = makeAnimorphosisDemoProject();
    REQUIRE(project.ok());
    auto c = projectGenericTree(*project);
    REQUIRE(c.ok());
    for (double u : {0.25, 0.5}) {
      const double t = kDemoMorphStartSec + u * (kDemoMorphEndSec - kDemoMorphStartSec);
      const FieldProgram prog = compileGeneric(*c, animorphosisTiming(*project), t);
      const ColorAgreement a = compareBlockColors(prog, 64, 17);
      INFO("t = " << t);
      CHECK(a.vertices > 2000);
      checkAgreement(a, prog);
    }
  }
  SECTION("the blob creature, mid-stride") {
    const FieldProgram prog = compileFieldProgram(makeBlobCreature(), 0.7);
    const ColorAgreement a = compareBlockColors(prog, 64, 3);
    CHECK(a.vertices > 2000);
    checkAgreement(a, prog);
  }
  SECTION("random trees of every node type") {
    int compared = 0;
    for (unsigned seed = 1; seed <= 16; ++seed) {
      std::mt19937 rng(seed);
      int nextId = 1;
      BlobTree t = test::treeOf(test::randomNode(rng, 4, nextId), 0.5f);
      paintRandomly(t.root, rng);
      const FieldProgram prog = compileFieldProgram(t, 0.0);
      if (prog.unbounded() || prog.tightBounds().empty()) continue;
      const ColorAgreement a = compareBlockColors(prog, 40, 1);
      if (a.vertices == 0) continue;
      INFO("seed " << seed);
      checkAgreement(a, prog);
      ++compared;
    }
    CHECK(compared >= 8);
  }
}

TEST_CASE("colour: an op specialised to none of its primitives has its first primitive's colour, a dropped operand's "
          "colour is kept (the whole walk's colours)",
          "[color]") {
  // blend(point, green, far below; union(point, red, above; convolution segment, blue)) specialised
  // to the segment alone: the red point's op is left holding no primitive (and the old walk read the
  // segment's index for it), the green point's op is dropped from the blend.
  BlobNode segment = test::convSegmentNode(4, {-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 0.3f);
  segment.vec3Param("color") = Vec3Track(kBlue);
  BlobTree t = test::treeOf(test::operatorNode(
      NodeType::Blend, 1,
      {coloredPoint(2, {0.0f, -40.0f, 0.0f}, kGreen),
       test::operatorNode(NodeType::Union, 3, {coloredPoint(5, {0.0f, 40.0f, 0.0f}, kRed), segment})}));
  const FieldProgram prog = compileFieldProgram(t, 0.0);
  REQUIRE(prog.primitiveCount() == 3);
  uint32_t segmentId = 0;
  for (const FieldOp& op : prog.ops)
    if (op.code == OpCode::Prims && op.primClass == PrimClass::Convolution) segmentId = op.primBegin;
  ActiveProgram active;
  prog.specialise({segmentId}, active);
  size_t emptyOps = 0;
  for (const FieldOp& op : active.ops) emptyOps += op.code == OpCode::Prims && op.count == 0;
  REQUIRE(emptyOps == 1);
  const ColorProgram cp(prog);
  // Near the segment (blue wins the union), and far from every primitive (0 everywhere: the blend
  // keeps its first operand's colour, the green point's), as the whole walk gives.
  const std::vector<glm::vec3> points = {{0.0f, 0.2f, 0.0f}, {0.5f, -0.1f, 0.1f}, {0.0f, 0.0f, 100.0f}};
  std::vector<float> x, y, z;
  for (const glm::vec3& p : points) {
    x.push_back(p.x);
    y.push_back(p.y);
    z.push_back(p.z);
  }
  std::vector<glm::vec4> got(points.size()), want(points.size());
  SurfaceColorEvaluator ev;
  ev.evaluateActive(cp, active, x.data(), y.data(), z.data(), int(points.size()), got.data());
  ev.evaluateFull(prog, points.data(), points.size(), want.data());
  for (size_t i = 0; i < points.size(); ++i) checkNear(glm::vec3(got[i]), glm::vec3(want[i]));
  checkNear(glm::vec3(got[0]), kBlue);
  checkNear(glm::vec3(got[1]), kBlue);
  checkNear(glm::vec3(got[2]), kGreen);
}

TEST_CASE("colour: a block kept from the previous frame keeps its colours, and is coloured again when only the "
          "colours changed",
          "[color]") {
  const FieldProgram red = compileFieldProgram(twoPoints(NodeType::Blend, kRed, kRed), 0.0);
  const FieldProgram blue = compileFieldProgram(twoPoints(NodeType::Blend, kBlue, kBlue), 0.0);
  for (float tolerance : {0.0f, 0.1f}) {
    INFO("tolerance " << tolerance << " cells");
    PolygonizeHistory history;
    PolygonizeSettings ps;
    ps.resolution = 40;
    ps.threads = 2;
    ps.colors = true;
    ps.history = &history;
    ps.reuseToleranceCells = tolerance;
    auto first = polygonize(red, ps);
    auto again = polygonize(red, ps);
    REQUIRE(first.ok());
    REQUIRE(again.ok());
    CHECK(again->stats.blocksReused > 0);
    REQUIRE(again->mesh.colors.size() == again->mesh.positions.size());
    for (const glm::vec4& c : again->mesh.colors) REQUIRE(glm::vec3(c) == kRed);
    auto second = polygonize(blue, ps);
    REQUIRE(second.ok());
    // The same field: within a tolerance its blocks are kept (and coloured again), without one
    // a colour change alone makes them new.
    if (tolerance > 0.0f) CHECK(second->stats.blocksReused > 0);
    else CHECK(second->stats.blocksReused == 0);
    REQUIRE(second->mesh.colors.size() == second->mesh.positions.size());
    REQUIRE(!second->mesh.colors.empty());
    for (const glm::vec4& c : second->mesh.colors) REQUIRE(glm::vec3(c) == kBlue);
  }
}

TEST_CASE("colour: a point between two primitives takes the blend weighted by their field contributions",
          "[color]") {
  FieldProgram prog = compileFieldProgram(twoPoints(NodeType::Blend, kRed, kBlue), 0.0);
  SurfaceColorEvaluator ev;
  // At x = 0.3: red's contribution (1 - 0.3^2)^3 = 0.753571, blue's (1 - 0.7^2)^3 = 0.132651 (R = 1,
  // k = 3, I = 1); red and blue are (1, 0, 0) and (0, 0, 1) in sRGB and in linear light alike, so
  // the blend is (0.753571, 0, 0.132651) / 0.886222 = (0.850319, 0, 0.149681).
  checkNear(ev.evaluatePoint(prog, {0.3f, 0.0f, 0.0f}), {0.850319f, 0.0f, 0.149681f});
  // Beyond blue's reach (R = 1) only red counts.
  checkNear(ev.evaluatePoint(prog, {-0.5f, 0.0f, 0.0f}), {1.0f, 0.0f, 0.0f});
  // Halfway: equal weights.
  checkNear(ev.evaluatePoint(prog, {0.5f, 0.0f, 0.0f}), {0.5f, 0.0f, 0.5f});
}

TEST_CASE("colour: a blend of many framed points weighs each by its own field (the walk's one-loop path for a mapped "
          "point and its one-colour sums), seeded",
          "[color]") {
  // Each child a Frame translating one coloured point (a mapped point primitive, as the animorphosis
  // demo's meta-primitives): the colour at x is sum w_k c_k / sum w_k with w_k = I_k (1 - d_k^2 /
  // R_k^2)^k_k of its own local point x - t_k, computed here from the definition. Stiffness 1..4 (the
  // evaluator's one-loop forms) and 2.5 (the general op), some frames far from the points (skipped
  // maps), runs of one colour next to mixed ones.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec3 palette[3] = {kRed, kBlue, kGreen};
  struct Child {
    glm::vec3 t, color;
    float radius, intensity, stiffness;
  };
  std::vector<Child> kids;
  BlobTree tree;
  tree.threshold = FloatTrack(0.5f);
  tree.root = makeBlobNode(NodeType::Blend, 1, "root");
  int id = 2;
  for (int k = 0; k < 150; ++k) {
    Child c;
    c.t = k % 10 == 9 ? glm::vec3(40.0f + float(k), 0.0f, 0.0f) : glm::vec3(u(rng), u(rng), u(rng));
    c.color = k < 40 ? kRed : palette[rng() % 3];
    c.radius = 0.6f + 0.5f * std::abs(u(rng));
    c.intensity = 0.5f + std::abs(u(rng));
    const float stiff[5] = {1.0f, 2.0f, 3.0f, 4.0f, 2.5f};
    c.stiffness = stiff[k % 5];
    BlobNode p = coloredPoint(id++, glm::vec3(0.0f), c.color, c.radius);
    p.floatParam("intensity") = FloatTrack(c.intensity);
    p.floatParam("stiffness") = FloatTrack(c.stiffness);
    BlobNode frame = makeBlobNode(NodeType::Frame, id++);
    frame.vec3Param("translation") = Vec3Track(c.t);
    frame.children.push_back(p);
    tree.root.children.push_back(frame);
    kids.push_back(c);
  }
  const FieldProgram prog = compileFieldProgram(tree, 0.0);
  std::vector<glm::vec3> points;
  for (int i = 0; i < 700; ++i) points.push_back(1.2f * glm::vec3(u(rng), u(rng), u(rng)));
  std::vector<glm::vec4> got(points.size()), full(points.size());
  SurfaceColorEvaluator ev;
  ev.evaluate(prog, points.data(), points.size(), got.data(), 2);
  ev.evaluateFull(prog, points.data(), points.size(), full.data());
  int weighed = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    glm::vec3 sum(0.0f);
    float w = 0.0f;
    for (const Child& c : kids) {
      const glm::vec3 d = points[i] - c.t;
      const float q = 1.0f - glm::dot(d, d) / (c.radius * c.radius);
      const float wk = q > 0.0f ? c.intensity * std::pow(q, c.stiffness) : 0.0f;
      sum += wk * c.color;
      w += wk;
    }
    if (!(w > 1e-3f)) continue;  // near no primitive: the rules' fallback colours, tested elsewhere
    ++weighed;
    INFO("point " << i);
    checkNear(glm::vec3(got[i]), sum / w, 2e-5f);
    checkNear(glm::vec3(full[i]), sum / w, 2e-5f);
  }
  CHECK(weighed > 500);
}

TEST_CASE("colour: union takes the larger operand's colour, difference the kept side's, maps move the point",
          "[color]") {
  SurfaceColorEvaluator ev;
  FieldProgram uni = compileFieldProgram(twoPoints(NodeType::Union, kRed, kBlue), 0.0);
  checkNear(ev.evaluatePoint(uni, {0.4f, 0.0f, 0.0f}), kRed);
  checkNear(ev.evaluatePoint(uni, {0.6f, 0.0f, 0.0f}), kBlue);
  FieldProgram diff = compileFieldProgram(twoPoints(NodeType::Difference, kRed, kBlue), 0.0);
  checkNear(ev.evaluatePoint(diff, {0.6f, 0.0f, 0.0f}), kRed);
  // A frame moving the blue point to x = 3: at x = 3 the colour is blue, at the origin red.
  BlobTree t = twoPoints(NodeType::Blend, kRed, kBlue);
  BlobNode frame = makeBlobNode(NodeType::Frame, 4);
  frame.vec3Param("translation") = Vec3Track(glm::vec3(2.0f, 0.0f, 0.0f));
  frame.children.push_back(t.root.children[1]);
  t.root.children[1] = frame;
  FieldProgram mapped = compileFieldProgram(t, 0.0);
  checkNear(ev.evaluatePoint(mapped, {3.0f, 0.0f, 0.0f}), kBlue);
  checkNear(ev.evaluatePoint(mapped, {0.0f, 0.0f, 0.0f}), kRed);
}

TEST_CASE("colour: a tree without colours is the clay tone, and JSON reads old files with it", "[color]") {
  BlobTree t;
  t.root = makeBlobNode(NodeType::Blend, 1, "root");
  BlobNode p = makeBlobNode(NodeType::Point, 2);
  p.floatParam("radius") = FloatTrack(1.0f);
  t.root.children.push_back(p);
  CHECK(t.root.children[0].vec3Param("color").evaluate(0.0) == kClayColorSrgb);
  FieldProgram prog = compileFieldProgram(t, 0.0);
  checkNear(SurfaceColorEvaluator().evaluatePoint(prog, {0.2f, 0.0f, 0.0f}), srgbToLinear(kClayColorSrgb));

  // A default colour is not written (an old tree saves as before) and reads back as the default.
  const std::string text = blobTreeSceneToString(t);
  CHECK(text.find("\"color\"") == std::string::npos);
  const char* old = R"({"format": "animorph-blobtree", "version": 1, "threshold": 1.0, "root": {"id": 1,
    "type": "blend", "children": [{"id": 2, "type": "point", "params": {"center": [0, 0, 0], "radius": 1}}]}})";
  auto read = parseBlobTreeScene(old, "old.json");
  REQUIRE(read.ok());
  CHECK(read->root.children[0].vec3Param("color").evaluate(0.0) == kClayColorSrgb);

  // A keyed colour round-trips.
  t.root.children[0].vec3Param("color").setKey(0.0, kRed);
  t.root.children[0].vec3Param("color").setKey(1.0, kBlue);
  auto back = parseBlobTreeScene(blobTreeSceneToString(t), "colored.json");
  REQUIRE(back.ok());
  CHECK(*back == t);
  checkNear(back->root.children[0].vec3Param("color").evaluate(0.5), 0.5f * (kRed + kBlue));

  // Out of range: refused, naming the node and the parameter.
  t.root.children[0].vec3Param("color") = Vec3Track(glm::vec3(1.5f, 0.0f, 0.0f));
  Status s = validateBlobTree(t);
  REQUIRE_FALSE(s.ok());
  CHECK_THAT(s.error(), Contains("'color'") && Contains("outside 0..1"));
}

TEST_CASE("colour: the CPU polygoniser gives every vertex the surface colour there", "[color]") {
  FieldProgram prog = compileFieldProgram(twoPoints(NodeType::Blend, kRed, kBlue), 0.0);
  PolygonizeSettings ps;
  ps.resolution = 48;
  ps.threads = 2;
  auto plain = polygonize(prog, ps);
  ps.colors = true;
  auto colored = polygonize(prog, ps);
  REQUIRE(plain.ok());
  REQUIRE(colored.ok());
  CHECK(plain->mesh.colors.empty());
  const TriangleMesh& m = colored->mesh;
  CHECK(m.positions == plain->mesh.positions);  // colour changes no geometry
  REQUIRE(m.colors.size() == m.positions.size());
  REQUIRE(m.positions.size() > 100);
  SurfaceColorEvaluator ev;
  size_t reddish = 0, bluish = 0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec4& c = m.colors[i];
    REQUIRE(c.a == 1.0f);
    CHECK(std::abs(c.r + c.b - 1.0f) < 1e-4f);  // a blend of red and blue only
    reddish += m.positions[i].x < 0.0f && c.r > 0.99f;
    bluish += m.positions[i].x > 1.0f && c.b > 0.99f;
    if (i % 97 == 0) checkNear(glm::vec3(c), ev.evaluatePoint(prog, m.positions[i]));
  }
  CHECK(reddish > 20);
  CHECK(bluish > 20);
}

TEST_CASE("colour: the animorphosis interpolates colours by s(t), and a null partner fades its colour with its shape",
          "[color][animorph]") {
  BlobTree a, b;
  a.root = makeBlobNode(NodeType::Blend, 1, "a");
  a.root.children.push_back(coloredPoint(2, glm::vec3(0.0f), kRed));
  b.root = makeBlobNode(NodeType::Blend, 1, "b");
  b.root.children.push_back(coloredPoint(2, glm::vec3(0.0f), kBlue));
  b.root.children.push_back(coloredPoint(3, glm::vec3(2.0f, 0.0f, 0.0f), kGreen, 0.3f));  // no partner in A
  CorrespondenceGraph g;
  g.links.push_back({1, 1, {}, 1.0f, true});
  g.links.push_back({2, 2, {}, 1.0f, true});
  auto c = buildGenericTree(a, b, g);
  REQUIRE(c.ok());
  AnimorphosisTiming timing;  // u = t over [0, 1], s(u) = 3u^2 - 2u^3 (the default curve)
  SurfaceColorEvaluator ev;
  // At u = 0.25, s = 3/16 - 2/64 = 0.15625: the point's colour is (0.84375, 0, 0.15625) in sRGB,
  // (0.84375^2.2, 0, 0.15625^2.2) = (0.688130, 0, 0.016842) in linear light. Behind the point (x < 0)
  // the small green one, growing out of the body, does not reach.
  FieldProgram quarter = compileGeneric(*c, timing, 0.25);
  checkNear(ev.evaluatePoint(quarter, {-0.3f, 0.0f, 0.0f}), {0.688130f, 0.0f, 0.016842f});
  // The green null partner: intensity (1 - s) 0 + s 1 = s, so at its own centre its weight is s
  // against the red-blue point's (1 - (d / 1)^2)^3 at distance d: its colour fades in with its shape.
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const FieldProgram prog = compileGeneric(*c, timing, t);
    const double s = 3.0 * t * t - 2.0 * t * t * t;
    // The green primitive's centre in this frame (the partner grows out of the body as it moves).
    glm::vec3 centre(0.0f);
    for (size_t i = 0; i < prog.skeletal.size(); ++i)
      if (prog.primitiveColor(PrimClass::Skeletal, uint32_t(i)) == kGreen) centre = prog.skeletal[i].skeleton.p0;
    const float d = glm::length(centre);
    const float w1 = d < 1.0f ? std::pow(1.0f - d * d, 3.0f) : 0.0f, wg = float(s);
    const glm::vec3 c1 = srgbToLinear(glm::mix(kRed, kBlue, float(s)));
    const glm::vec3 want = w1 + wg > 0.0f ? (w1 * c1 + wg * kGreen) / (w1 + wg) : c1;
    INFO("t = " << t << ", green centre x = " << centre.x);
    checkNear(ev.evaluatePoint(prog, centre), want, 1e-4f);
    if (t == 0.0) CHECK(ev.evaluatePoint(prog, centre).g == 0.0f);
    if (t == 1.0) CHECK(ev.evaluatePoint(prog, centre).g > 0.99f);
  }
}

TEST_CASE("colour: particles converted from a coloured shape carry the colour of the point they came from",
          "[color][particles]") {
  FieldProgram prog = compileFieldProgram(twoPoints(NodeType::Blend, kRed, kBlue), 0.0);
  ConvertToParticlesSettings s;
  s.count = 300;
  s.calibrationCells = 100'000;
  auto r = convertToParticles(prog, s);
  REQUIRE(r.ok());
  size_t red = 0, blue = 0;
  for (const BlobNode& p : r->tree.root.children) {
    const glm::vec3 c = p.vec3Param("color").evaluate(0.0), x = p.vec3Param("center").evaluate(0.0);
    // The particle's colour is the shape's at its centre (sRGB of the blend in linear light).
    checkNear(c, linearToSrgb(SurfaceColorEvaluator().evaluatePoint(prog, x)), 1e-4f);
    red += x.x < -0.05f && c.r > 0.999f;
    blue += x.x > 1.05f && c.b > 0.999f;
  }
  CHECK(red > 10);
  CHECK(blue > 10);
  // A shape without colours: the particles keep the default (not written to files).
  BlobTree plain = twoPoints(NodeType::Blend, kClayColorSrgb, kClayColorSrgb);
  auto q = convertToParticles(compileFieldProgram(plain, 0.0), s);
  REQUIRE(q.ok());
  for (const BlobNode& p : q->tree.root.children) REQUIRE(p.vec3Param("color") == Vec3Track(kClayColorSrgb));
}
