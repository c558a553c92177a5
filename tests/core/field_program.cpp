#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "core/blobtree/compile.h"
#include "core/field/field_program.h"
#include "util/blob_builders.h"
#include "util/reference_field.h"

using namespace animorph;
using namespace animorph::test;

namespace {

glm::vec3 randomIn(std::mt19937& rng, float s) {
  std::uniform_real_distribution<float> u(-s, s);
  return {u(rng), u(rng), u(rng)};
}

// Values and gradients of p (compiled from tree at t = 0) at 64 random points against the
// recursive reference.
void checkAgainstReference(const FieldProgram& p, const BlobTree& tree, std::mt19937& rng) {
  FieldEvaluator ev;
  ActiveProgram all;
  p.specialiseAll(all);
  for (int i = 0; i < 64; ++i) {
    glm::vec3 q = randomIn(rng, 0.6f);
    float f, gx, gy, gz;
    ev.evaluate(p, all, &q.x, &q.y, &q.z, 1, &f, &gx, &gy, &gz);
    glm::vec3 gr;
    CHECK(f == Approx(referenceField(tree, 0.0, q, &gr)).margin(1e-5));
    CHECK(glm::length(glm::vec3(gx, gy, gz) - gr) <= 1e-3f * std::max(1.0f, glm::length(gr)));
  }
}

}  // namespace

TEST_CASE("FieldProgram equals the recursive reference on random trees", "[field_program]") {
  int compared = 0;
  for (unsigned seed = 100; seed < 160; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    for (double t : {0.0, 0.37, 1.0}) {
      FieldProgram p = compileFieldProgram(tree, t);
      FieldEvaluator ev;
      // A batch through the SoA path, and the reference point by point.
      std::vector<glm::vec3> pts;
      for (int i = 0; i < 64; ++i) pts.push_back(randomIn(rng, 0.8f));
      std::vector<float> x, y, z, f(pts.size()), gx(pts.size()), gy(pts.size()), gz(pts.size());
      for (auto& q : pts) {
        x.push_back(q.x);
        y.push_back(q.y);
        z.push_back(q.z);
      }
      ActiveProgram all;
      p.specialiseAll(all);
      ev.evaluate(p, all, x.data(), y.data(), z.data(), int(pts.size()), f.data(), gx.data(), gy.data(), gz.data());
      for (size_t i = 0; i < pts.size(); ++i) {
        glm::vec3 gr;
        float fr = referenceField(tree, t, pts[i], &gr);
        INFO("seed " << seed << " t " << t << " point " << i);
        // The convolution cut (1e-3 T) may fall either side for float vs double.
        CHECK(f[i] == Approx(fr).margin(2e-3));
        if (std::abs(f[i] - fr) < 1e-4f)
          CHECK(glm::length(glm::vec3(gx[i], gy[i], gz[i]) - gr) <= 1e-2f * std::max(1.0f, glm::length(gr)));
        ++compared;
      }
    }
  }
  CHECK(compared == 60 * 3 * 64);
}

TEST_CASE("a program specialised to a region gives the same values there", "[field_program]") {
  for (unsigned seed = 200; seed < 230; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    FieldProgram p = compileFieldProgram(tree, 0.2);
    FieldEvaluator ev;
    for (int r = 0; r < 8; ++r) {
      Bounds box;
      glm::vec3 c = randomIn(rng, 0.6f);
      box.add(c - glm::vec3(0.1f));
      box.add(c + glm::vec3(0.1f));
      std::vector<uint32_t> active;
      p.primitivesReaching(box, active);
      ActiveProgram spec, all;
      p.specialise(active, spec);
      p.specialiseAll(all);
      CHECK(spec.primitiveCount <= p.primitiveCount());
      std::vector<float> x, y, z;
      for (int i = 0; i < 40; ++i) {
        glm::vec3 q = box.min + (box.max - box.min) * (0.5f + 0.5f * randomIn(rng, 1.0f));
        x.push_back(q.x);
        y.push_back(q.y);
        z.push_back(q.z);
      }
      std::vector<float> a(x.size()), b(x.size());
      ev.evaluate(p, spec, x.data(), y.data(), z.data(), int(x.size()), a.data());
      ev.evaluate(p, all, x.data(), y.data(), z.data(), int(x.size()), b.data());
      INFO("seed " << seed);
      CHECK(a == b);  // bit for bit: culled primitives contribute exactly 0 there
      // The interval bound holds every value in the box's ball.
      Interval iv = p.interval(spec, box.center(), 0.5f * box.diagonal());
      for (float v : b) {
        CHECK(v >= iv.lo - 1e-4f);
        CHECK(v <= iv.hi + 1e-4f);
      }
    }
  }
}

TEST_CASE("outside the program's bounds the field is outside", "[field_program]") {
  // Half the points in a shell just outside the bounds (out to a quarter of the box's size, where
  // a box that cut into the surface shows), half anywhere in [-2, 2]^3; every point outside the
  // bounds is checked, and counted: the case must have looked at many, most of them near the box.
  int bounded = 0, checked = 0, nearBox = 0;
  for (unsigned seed = 300; seed < 330; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    FieldProgram p = compileFieldProgram(tree, 0.5);
    if (p.unbounded()) continue;
    ++bounded;
    const Bounds b = p.bounds();
    const glm::vec3 margin = 0.25f * b.size() + glm::vec3(0.01f);
    FieldEvaluator ev;
    for (int i = 0; i < 200; ++i) {
      const bool shell = i % 2 == 0 && !b.empty();
      glm::vec3 x = randomIn(rng, 2.0f);
      if (shell) {
        const glm::vec3 u = 0.5f * (randomIn(rng, 1.0f) + glm::vec3(1.0f));  // in [0, 1]^3
        x = b.min - margin + u * (b.size() + 2.0f * margin);
      }
      bool in = !b.empty() && x.x >= b.min.x && x.y >= b.min.y && x.z >= b.min.z && x.x <= b.max.x &&
                x.y <= b.max.y && x.z <= b.max.z;
      if (in) continue;
      ++checked;
      nearBox += shell;
      INFO("seed " << seed << ", point " << x.x << " " << x.y << " " << x.z);
      CHECK(ev.evaluatePoint(p, x) < 0.0f);
    }
  }
  INFO(bounded << " bounded programs of 30, " << checked << " points checked, " << nearBox << " near the box");
  CHECK(bounded >= 10);
  CHECK(checked >= 100 * bounded);
  CHECK(nearBox >= 50 * bounded);
}

TEST_CASE("primitives of one class under one operator share one op", "[field_program]") {
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  for (int i = 0; i < 10; ++i)
    root.children.push_back(convSegmentNode(2 + i, {0.1f * i, 0, 0}, {0.1f * i + 0.1f, 0, 0}, 0.05f));
  root.children.push_back(pointNode(20, {0, 0.2f, 0}, 0.2f));
  root.children.push_back(pointNode(21, {0, 0.4f, 0}, 0.2f));
  FieldProgram p = compileFieldProgram(treeOf(root), 0.0);
  REQUIRE(p.ops.size() == 3);  // Prims(10 convolution), Prims(2 skeletal), Sum(2)
  CHECK(p.ops[0].code == OpCode::Prims);
  CHECK(p.ops[0].count == 10);
  CHECK(p.ops[1].count == 2);
  CHECK(p.ops[2].code == OpCode::Sum);
  CHECK(p.ops[2].count == 2);
  CHECK(p.primitiveCount() == 12);
}

namespace {

// A flat Coons patch over [x0, x0 + 0.3] x [-0.15, 0.15] at height y, `cells` per side, radius 0.15.
BlobNode coonsPatchNode(int id, float x0, float y, int cells) {
  BlobNode n = makeBlobNode(NodeType::CoonsPatch, id);
  auto edge = [](glm::vec3 a, glm::vec3 b) { return ControlPoints{Vec3Track(a), Vec3Track(0.5f * (a + b)), Vec3Track(b)}; };
  glm::vec3 p00{x0, y, -0.15f}, p10{x0 + 0.3f, y, -0.15f}, p01{x0, y, 0.15f}, p11{x0 + 0.3f, y + 0.1f, 0.15f};
  n.pointsParam("bottom") = edge(p00, p10);
  n.pointsParam("top") = edge(p01, p11);
  n.pointsParam("left") = edge(p00, p01);
  n.pointsParam("right") = edge(p10, p11);
  n.floatParam("resolution") = FloatTrack(float(cells));
  n.floatParam("radius") = FloatTrack(0.15f);
  return n;
}

}  // namespace

TEST_CASE("Coons patches under a union join the run of primitives, with the reference's values", "[field_program]") {
  std::mt19937 rng(7);
  BlobNode u = makeBlobNode(NodeType::Union, 1);
  for (int i = 0; i < 3; ++i) u.children.push_back(coonsPatchNode(2 + i, -0.45f + 0.3f * float(i), 0.05f * float(i), 2));
  u.children.push_back(pointNode(9, {0, 0.25f, 0}, 0.2f));
  BlobTree unionTree = treeOf(u, 0.5f);
  FieldProgram p = compileFieldProgram(unionTree, 0.0);
  REQUIRE(p.ops.size() == 1);  // one Prims op: 3 patches x 8 triangles and the point, max-combined
  CHECK(p.ops[0].code == OpCode::Prims);
  CHECK(p.ops[0].combineMax);
  CHECK(p.ops[0].count == 25);
  checkAgainstReference(p, unionTree, rng);
  // Under a blend each patch stays one operand (a sum of the patches' maxima).
  BlobNode b = u;
  b.type = NodeType::Blend;
  BlobTree blendTree = treeOf(b, 0.5f);
  FieldProgram q = compileFieldProgram(blendTree, 0.0);
  CHECK(std::count_if(q.ops.begin(), q.ops.end(), [](const FieldOp& op) { return op.code == OpCode::Prims; }) == 4);
  checkAgainstReference(q, blendTree, rng);
}

TEST_CASE("wide operators fold into a shallow stack with the values of the tree", "[field_program]") {
  // 23 children that each push their own operand (a frame around a point): before folding the
  // stack held 23 values, beyond the GPU's 16 (a spline of nodes with 20 copies did the same).
  std::mt19937 rng(5);
  for (NodeType type : {NodeType::Blend, NodeType::Union, NodeType::Intersection, NodeType::HyperBlend}) {
    int id = 1;
    BlobNode root = makeBlobNode(type, id++);
    if (type == NodeType::HyperBlend) root.floatParam("q") = FloatTrack(3.0f);
    for (int i = 0; i < 23; ++i) {
      BlobNode frame = makeBlobNode(NodeType::Frame, id++);
      frame.vec3Param("translation") = Vec3Track(glm::vec3(0.04f * float(i) - 0.44f, 0.0f, 0.0f));
      // Intersection: balls around the origin, so the intersection is not empty.
      glm::vec3 c = type == NodeType::Intersection ? -frame.vec3Param("translation").evaluate(0.0) : glm::vec3(0.0f);
      frame.children.push_back(pointNode(id++, c, type == NodeType::Intersection ? 0.7f : 0.12f));
      root.children.push_back(frame);
    }
    BlobTree tree = treeOf(root, 0.5f);
    FieldProgram p = compileFieldProgram(tree, 0.0);
    INFO("node type " << int(type));
    CHECK(p.maxStack() <= int(kFoldOperands));
    uint32_t operators = 0;
    for (const FieldOp& op : p.ops) {
      if (op.code == OpCode::Prims || op.code == OpCode::Const || op.code == OpCode::BeginMap || op.code == OpCode::EndMap)
        continue;
      CHECK(op.count <= kFoldOperands);
      ++operators;
    }
    CHECK(operators == 8);  // 4 + 3 * 6 + 1: ceil(22 / 3) operators
    checkAgainstReference(p, tree, rng);
  }
}

TEST_CASE("operands of commuting operators nested deep are emitted deepest first", "[field_program]") {
  // Blends (unions, intersections) nested 20 deep, each holding a bead and the next one: in the
  // given order each level leaves its bead waiting (20 values on the stack, beyond the GPU's 16);
  // levels whose given order would stack more than 8 take the deeper operand first.
  std::mt19937 rng(9);
  for (NodeType type : {NodeType::Blend, NodeType::Union, NodeType::Intersection}) {
    int id = 1;
    const float r = type == NodeType::Intersection ? 0.9f : 0.2f;
    BlobNode inner = pointNode(id++, glm::vec3(0.0f), r);
    for (int i = 0; i < 20; ++i)
      inner = operatorNode(type, id++, {pointNode(id++, glm::vec3(0.02f * float(i + 1), 0.0f, 0.0f), r), inner});
    BlobTree tree = treeOf(inner, 0.5f);
    FieldProgram p = compileFieldProgram(tree, 0.0);
    INFO("node type " << int(type));
    CHECK(p.maxStack() <= 8);
    checkAgainstReference(p, tree, rng);
  }
  // Shallow trees keep their order (and so their primitive ids): a blend of a frame and a bead.
  int id = 1;
  BlobNode frame = makeBlobNode(NodeType::Frame, id++);
  frame.children.push_back(pointNode(id++, glm::vec3(0.0f), 0.2f));
  FieldProgram shallow =
      compileFieldProgram(treeOf(operatorNode(NodeType::Blend, id++, {pointNode(id++, glm::vec3(0.3f, 0, 0), 0.2f), frame})), 0.0);
  REQUIRE(shallow.ops.size() == 5);  // Prims(bead), BeginMap, Prims(frame's point), EndMap, Sum(2)
  CHECK(shallow.ops[0].code == OpCode::Prims);
  CHECK(shallow.ops[1].code == OpCode::BeginMap);
}

TEST_CASE("points evaluated alone give the values and gradients of one batch spread over the tree",
          "[field_program]") {
  // Alone, a point's box is the point itself: the evaluator skips every map subtree and every
  // skeletal primitive out of its reach. In a batch spread over the whole tree nothing is skipped.
  size_t skippable = 0;
  for (unsigned seed = 300; seed < 340; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 4, id), 0.5f);
    FieldProgram p = compileFieldProgram(tree, 0.3);
    ActiveProgram all;
    p.specialiseAll(all);
    FieldEvaluator ev;
    std::vector<float> x, y, z;
    for (int i = 0; i < 200; ++i) {
      glm::vec3 q = randomIn(rng, 0.8f);
      x.push_back(q.x);
      y.push_back(q.y);
      z.push_back(q.z);
    }
    const int n = int(x.size());
    std::vector<float> f(n), gx(n), gy(n), gz(n);
    ev.evaluate(p, all, x.data(), y.data(), z.data(), n, f.data(), gx.data(), gy.data(), gz.data());
    for (int i = 0; i < n; ++i) {
      float f1, gx1, gy1, gz1;
      ev.evaluate(p, all, &x[i], &y[i], &z[i], 1, &f1, &gx1, &gy1, &gz1);
      INFO("seed " << seed << " point " << i);
      CHECK(f1 == f[i]);  // bit for bit: what is skipped contributes exactly nothing there
      CHECK(gx1 == gx[i]);
      CHECK(gy1 == gy[i]);
      CHECK(gz1 == gz[i]);
    }
    for (size_t m = 0; m < p.maps.size(); ++m) {
      const Bounds& r = p.mapReach(uint32_t(m));
      skippable += !r.empty() && std::min({r.size().x, r.size().y, r.size().z}) < 1.6f;  // smaller than the sampled cube: some points miss it
    }
  }
  CHECK(skippable > 20);  // the random trees do have maps that points can miss
}

TEST_CASE("the Remap op scales and bounds a potential, keeps its surface, with exact gradients and intervals",
          "[field_program]") {
  const float T = 0.8f, K = 4.0f, s = 0.6f;
  auto build = [&](float scale, float bound) {
    FieldProgram p;
    p.threshold = T;
    p.addConvolution(glm::vec3(-0.3f, 0, 0), glm::vec3(0.3f, 0.05f, 0), 0.12f, 15.0f, 1e-3f, false);
    const float prm[2] = {scale, bound};
    p.addOperator(OpCode::Remap, 1, prm, 2);
    p.finish();
    return p;
  };
  FieldProgram plain;
  plain.threshold = T;
  plain.addConvolution(glm::vec3(-0.3f, 0, 0), glm::vec3(0.3f, 0.05f, 0), 0.12f, 15.0f, 1e-3f, false);
  plain.finish();
  const FieldProgram bounded = build(1.0f, K), scaledBounded = build(s, K), scaled = build(s, 0.0f);
  FieldEvaluator ev;
  std::mt19937 rng(7);
  float peak = 0.0f;
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 q = randomIn(rng, 0.4f);
    const float p = ev.evaluatePoint(plain, q) + T;
    peak = std::max(peak, p);
    const float h = K * T * p / ((K - 1.0f) * T + p);
    CHECK(ev.evaluatePoint(bounded, q) + T == Approx(h).epsilon(1e-5).margin(1e-6));
    CHECK(ev.evaluatePoint(scaledBounded, q) + T == Approx(s * h).epsilon(1e-5).margin(1e-6));
    CHECK(ev.evaluatePoint(scaled, q) + T == Approx(s * p).epsilon(1e-5).margin(1e-6));
    CHECK(h <= K * T);
    // The surface p = T stays where it was: same sign inside and outside.
    CHECK((ev.evaluatePoint(bounded, q) >= 0.0f) == (p >= T));
    // Gradients against central differences.
    glm::vec3 g;
    ev.evaluatePoint(scaledBounded, q, &g);
    const float e = 1e-3f;
    for (int k = 0; k < 3; ++k) {
      glm::vec3 a = q, b = q;
      a[k] -= e;
      b[k] += e;
      const float fd = (ev.evaluatePoint(scaledBounded, b) - ev.evaluatePoint(scaledBounded, a)) / (2.0f * e);
      CHECK(g[k] == Approx(fd).margin(2e-3f * std::max(1.0f, glm::length(g))));
    }
    // The interval over a ball around q holds the values in it.
    ActiveProgram all;
    scaledBounded.specialiseAll(all);
    const Interval iv = scaledBounded.interval(all, q, 0.02f);
    for (int j = 0; j < 8; ++j) {
      const float v = ev.evaluatePoint(scaledBounded, q + 0.02f * glm::normalize(randomIn(rng, 1.0f)));
      CHECK(v >= iv.lo - 1e-5f);
      CHECK(v <= iv.hi + 1e-5f);
    }
  }
  CHECK(peak > 2.0f * T);  // the points reached the part where bounding matters
}

TEST_CASE("a program compiled into a kept one equals a fresh compile of the same tree", "[field_program]") {
  FieldProgram kept;
  std::mt19937 rng(41);
  FieldEvaluator ev;
  for (unsigned seed = 300; seed < 320; ++seed) {
    std::mt19937 treeRng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(treeRng, 3, id), 0.5f);
    const uint64_t before = kept.identity();
    compileFieldProgram(tree, 0.37, kept);  // over the previous seed's program
    FieldProgram fresh = compileFieldProgram(tree, 0.37);
    INFO("seed " << seed);
    CHECK(kept.identity() != before);
    REQUIRE(kept.ops.size() == fresh.ops.size());
    for (size_t i = 0; i < fresh.ops.size(); ++i) {
      CHECK(kept.ops[i].code == fresh.ops[i].code);
      CHECK(kept.ops[i].count == fresh.ops[i].count);
      CHECK(kept.ops[i].first == fresh.ops[i].first);
      CHECK(kept.ops[i].emptyValue == fresh.ops[i].emptyValue);
    }
    CHECK(kept.primitiveCount() == fresh.primitiveCount());
    CHECK(kept.maps.size() == fresh.maps.size());
    CHECK(kept.bounds().min == fresh.bounds().min);
    CHECK(kept.bounds().max == fresh.bounds().max);
    CHECK(kept.maxStack() == fresh.maxStack());
    for (int k = 0; k < 32; ++k) {
      glm::vec3 q = randomIn(rng, 0.8f);
      CHECK(ev.evaluatePoint(kept, q) == ev.evaluatePoint(fresh, q));
    }
  }
}

TEST_CASE("a wide blend of small mapped primitives gives, in small runs that skip most of them, the values of one batch",
          "[field_program]") {
  // Like a meta-primitive's instances: many small primitives, each under its own map, blended. A
  // run of points near one end skips most map subtrees (the evaluator then only flags their zero
  // operands), including the first operands of the folded sums, and a union and a difference
  // take zero operands as well.
  std::mt19937 rng(77);
  int id = 1;
  auto instances = [&](glm::vec3 from, glm::vec3 to, int count) {
    std::vector<BlobNode> frames;
    for (int i = 0; i < count; ++i) {
      BlobNode frame = makeBlobNode(NodeType::Frame, id++);
      float s = float(i) / float(count - 1);
      frame.vec3Param("translation") = Vec3Track(from + s * (to - from));
      frame.quatParam("rotation") = QuatTrack(glm::angleAxis(0.3f * float(i), glm::normalize(glm::vec3(1, 2, 3))));
      frame.vec3Param("scale") = Vec3Track(glm::vec3(0.9f + 0.01f * float(i % 7)));
      frame.children.push_back(pointNode(id++, glm::vec3(0.0f), 0.12f, 0.8f));
      frames.push_back(std::move(frame));
    }
    return operatorNode(NodeType::Blend, id++, std::move(frames));
  };
  BlobNode a = instances({-0.7f, 0, 0}, {0.7f, 0, 0}, 40);
  BlobNode b = instances({0, -0.7f, 0.05f}, {0, 0.7f, 0.05f}, 30);
  BlobNode c = instances({-0.3f, 0.2f, -0.1f}, {0.3f, 0.2f, 0.1f}, 12);
  BlobTree tree = treeOf(operatorNode(NodeType::Difference, id++,
                                      {operatorNode(NodeType::Union, id++, {std::move(a), std::move(b)}), std::move(c)}));
  FieldProgram p = compileFieldProgram(tree, 0.0);
  ActiveProgram all;
  p.specialiseAll(all);
  FieldEvaluator ev;
  // Runs of 27 points in small cubes along the three chains and elsewhere, then all of them at once.
  std::vector<float> x, y, z;
  const int runs = 24, perRun = 27;
  for (int r = 0; r < runs; ++r) {
    glm::vec3 centre = randomIn(rng, 0.75f);
    if (r % 3 == 0) centre = {-0.75f + 0.065f * float(r), 0.0f, 0.0f};
    for (int k = 0; k < perRun; ++k) {
      glm::vec3 q = centre + glm::vec3(0.02f * float(k % 3), 0.02f * float((k / 3) % 3), 0.02f * float(k / 9));
      x.push_back(q.x);
      y.push_back(q.y);
      z.push_back(q.z);
    }
  }
  const int n = int(x.size());
  std::vector<float> f(n), gx(n), gy(n), gz(n), v(n);
  ev.evaluate(p, all, x.data(), y.data(), z.data(), n, f.data(), gx.data(), gy.data(), gz.data());
  ev.evaluate(p, all, x.data(), y.data(), z.data(), n, v.data());
  int inside = 0;
  for (int r = 0; r < runs; ++r) {
    const int o = r * perRun;
    float rf[perRun], rgx[perRun], rgy[perRun], rgz[perRun], rv[perRun];
    ev.evaluate(p, all, &x[o], &y[o], &z[o], perRun, rf, rgx, rgy, rgz);
    ev.evaluate(p, all, &x[o], &y[o], &z[o], perRun, rv);
    for (int k = 0; k < perRun; ++k) {
      INFO("run " << r << " point " << k);
      CHECK(rf[k] == f[o + k]);  // bit for bit
      CHECK(rv[k] == v[o + k]);
      CHECK(rv[k] == f[o + k]);
      CHECK(rgx[k] == gx[o + k]);
      CHECK(rgy[k] == gy[o + k]);
      CHECK(rgz[k] == gz[o + k]);
      glm::vec3 q(x[o + k], y[o + k], z[o + k]);
      CHECK(rf[k] == Approx(referenceField(tree, 0.0, q)).margin(1e-5));
      inside += rf[k] >= 0.0f;
    }
  }
  CHECK(inside > 0);  // some runs lie inside the chains
  CHECK(inside < runs * perRun);
}
