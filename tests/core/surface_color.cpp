// BlobTree colour (docs/blobtree.md, "Colour"): the primitives' colour parameter, its blend at a
// point of the surface weighted by the primitives' field contributions, the operators' rules, the
// JSON default for files without colours, the polygonised meshes' vertex colours, and the
// animorphosis' interpolation of colours (a null partner fading its colour with its shape).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/generic_tree.h"
#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "core/field/surface_color.h"
#include "core/particles/convert_to_particles.h"
#include "core/poly/polygonizer.h"

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

}  // namespace

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
