#include <catch2/catch.hpp>

#include <cstring>
#include <functional>
#include <random>

#include "core/animorphosis/compile_generic.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/poly/preview_polygonizer.h"
#include "demo/animorphosis_demo.h"
#include "core/project/animorphosis_project.h"
#include "util/animorph_fixtures.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// Every number of a program as bits, in a fixed order: two programs are byte-identical (for
// the evaluators, the GPU upload and the polygoniser) when their streams are equal.
struct Bits {
  std::vector<uint32_t> words;
  void add(uint32_t w) { words.push_back(w); }
  void add(float f) {
    uint32_t w;
    std::memcpy(&w, &f, sizeof w);
    words.push_back(w);
  }
  void add(const glm::vec3& v) {
    for (int k = 0; k < 3; ++k) add(v[k]);
  }
  void add(const glm::mat3& m) {
    for (int k = 0; k < 3; ++k) add(m[k]);
  }
  void add(const Bounds& b) {
    add(b.min);
    add(b.max);
  }
  void add(const std::vector<float>& v) {
    add(uint32_t(v.size()));
    for (float f : v) add(f);
  }
};

Bits programBits(const FieldProgram& p) {
  Bits b;
  b.add(p.threshold);
  b.add(uint32_t(p.ops.size()));
  for (const FieldOp& o : p.ops) {
    b.add(uint32_t(o.code) | uint32_t(o.primClass) << 8 | uint32_t(o.combineMax) << 16);
    for (uint32_t w : {o.first, o.count, o.primBegin, o.param, o.subtreeBegin}) b.add(w);
    b.add(o.emptyValue);
  }
  b.add(p.params);
  b.add(uint32_t(p.maps.size()));
  for (const SpaceMap& m : p.maps) {
    b.add(uint32_t(m.kind));
    b.add(m.linear);
    b.add(m.origin);
    b.add(m.forwardLinear);
    for (float f : {m.length, m.k0, m.k1}) b.add(f);
  }
  b.add(uint32_t(p.skeletal.size()));
  for (const SkeletalPrimitive& s : p.skeletal) {
    b.add(uint32_t(s.skeleton.kind));
    for (const glm::vec3& v : {s.skeleton.p0, s.skeleton.p1, s.skeleton.p2}) b.add(v);
    for (float f : {s.skeleton.r0, s.skeleton.r1, s.radius, s.intensity, s.stiffness}) b.add(f);
    b.add(uint32_t(s.skeleton.curveCount));
    b.add(s.curveFirst);
  }
  for (const SkeletalReach& r : p.skeletalReach) {
    b.add(r.a);
    b.add(r.b);
    b.add(r.reach);
  }
  b.add(uint32_t(p.curvePoints.size()));
  for (const glm::vec3& v : p.curvePoints) b.add(v);
  const ConvolutionData& c = p.convolution;
  for (const auto* v : {&c.bx, &c.by, &c.bz, &c.ax, &c.ay, &c.az, &c.length, &c.weight, &c.sharpness, &c.cut2}) b.add(*v);
  b.add(uint32_t(p.capsules.size()));
  for (const CapsulePrimitive& k : p.capsules) {
    b.add(k.a);
    b.add(k.b);
    b.add(k.radius);
  }
  b.add(uint32_t(p.primitiveBounds.size()));
  for (const PrimitiveBound& pb : p.primitiveBounds) {
    b.add(pb.a);
    b.add(pb.b);
    b.add(pb.radius);
    b.add(pb.box);
  }
  b.add(p.bounds());
  b.add(uint32_t(p.unbounded()) | uint32_t(p.maxStack()) << 8 | uint32_t(p.maxMapDepth()) << 16);
  for (uint32_t i = 0; i < p.maps.size(); ++i) b.add(p.mapReach(i));
  return b;
}

// The direct program against the snapshot's at time t, word for word (the first difference named).
void requireSameProgram(const FieldProgram& direct, const FieldProgram& snapshot, double t) {
  const std::vector<uint32_t> a = programBits(direct).words, b = programBits(snapshot).words;
  size_t first = 0;
  while (first < a.size() && first < b.size() && a[first] == b[first]) ++first;
  INFO("t = " << t << ": " << a.size() << " and " << b.size() << " words, first difference at word " << first
              << "; " << direct.ops.size() << " ops, " << direct.primitiveCount() << " primitives");
  REQUIRE(a == b);
}

// A seeded generic tree: a random creature and a perturbed copy with some blends made unions (their
// pairs bridged), most nodes linked, some with their own s(u). bridged: the blends made unions.
GenericTree seededGenericTree(unsigned seed, int& bridged) {
  std::mt19937 rng(seed);
  BlobTree a = randomCreature(rng, 80);
  std::unordered_map<int, int> idMap;
  BlobTree b = perturbedCopy(a, {0.4f, 0.1f, 0.0f}, 1.3f, rng, idMap, 0.05f);
  bridged = 0;
  std::function<void(BlobNode&)> bridge = [&](BlobNode& n) {
    if (n.type == NodeType::Blend && &n != &b.root && rng() % 3 == 0) {
      n.type = NodeType::Union;
      ++bridged;
    }
    for (BlobNode& k : n.children) bridge(k);
  };
  bridge(b.root);
  CorrespondenceGraph g;
  std::function<void(const BlobNode&)> link = [&](const BlobNode& n) {
    if (n.id != a.root.id && rng() % 5 != 0) {
      g.links.push_back({n.id, idMap.at(n.id), {}, 1.0f, true});
      if (rng() % 4 == 0) g.links.back().sOverride = hermiteRampTrack(0.0f, 2.0f);
    }
    for (const BlobNode& k : n.children) link(k);
  };
  link(a.root);
  auto c = buildGenericTree(a, b, g);
  INFO("seed " << seed << ", " << bridged << " blends made unions: " << (c.ok() ? "" : c.error()));
  REQUIRE(c.ok());
  return std::move(*c);
}

// The timing of the seeded trees' morph.
AnimorphosisTiming seededTiming() {
  AnimorphosisTiming timing;
  timing.startSec = 0.5;
  timing.endSec = 1.5;
  timing.target.speed = 1.5;
  return timing;
}

}  // namespace

TEST_CASE("compile generic: the demo's C(t) compiled directly is the snapshot's program bit for bit",
          "[animorph][compile]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  const AnimorphosisTiming timing = animorphosisTiming(*p);
  // What the times below cover: overrides, bridged pairs, null partners, both meta-primitives.
  int bridged = 0, splines = 0, coons = 0;
  std::function<void(const GenericNode&)> count = [&](const GenericNode& g) {
    bridged += g.a.type != g.b.type;
    splines += g.a.type == NodeType::SplineOfNodes;
    coons += g.a.type == NodeType::CoonsPatch;
    for (const GenericNode& k : g.children) count(k);
  };
  count(c->root);
  INFO(c->sCurves.size() << " overrides, " << bridged << " bridged pairs, " << c->nullPartners << " null partners, "
                         << splines << " splines of nodes, " << coons << " Coons patches");
  CHECK(!c->sCurves.empty());
  CHECK(c->nullPartners > 0);
  CHECK(splines > 0);
  CHECK(coons > 0);

  GenericProgramCompiler compiler(*c);
  CHECK(compiler.nodeCount() == c->size());
  FieldProgram kept;  // one program rewritten every frame, as the editor keeps it
  std::vector<double> times = {0.0, kDemoMorphStartSec - 0.5, kDemoMorphStartSec, kDemoMorphEndSec,
                               kDemoMorphEndSec + 1.3};
  for (int k = 1; k < 12; ++k)
    times.push_back(kDemoMorphStartSec + (kDemoMorphEndSec - kDemoMorphStartSec) * k / 12.0 + 0.013 * k);
  times.push_back(kDemoMorphStartSec + 0.001);  // s just above 0, then back to the middle
  times.push_back(0.5 * (kDemoMorphStartSec + kDemoMorphEndSec));
  std::vector<uint32_t> primitives;
  for (double t : times) {
    compiler.compile(timing, t, kept);
    const FieldProgram ref = compileFieldProgram(instantiateGeneric(*c, timing, t), 0.0);
    requireSameProgram(kept, ref, t);
    primitives.push_back(uint32_t(kept.primitiveCount()));
  }
  // The program's structure changes over the interval (bridged pairs, splines): each compile built it again.
  CHECK(*std::max_element(primitives.begin(), primitives.end()) >
        *std::min_element(primitives.begin(), primitives.end()));

  // And the field at random points, direct against the snapshot's program at one time.
  const double mid = 4.1;
  compiler.compile(timing, mid, kept);
  const FieldProgram ref = compileGeneric(*c, timing, mid);
  std::mt19937 rng(7);
  const Bounds box = ref.bounds();
  REQUIRE_FALSE(box.empty());
  std::uniform_real_distribution<float> x(0.0f, 1.0f);
  FieldEvaluator ev;
  int inside = 0;
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 q = box.min + (box.max - box.min) * glm::vec3(x(rng), x(rng), x(rng));
    glm::vec3 g1, g2;
    const float f1 = ev.evaluatePoint(kept, q, &g1), f2 = ev.evaluatePoint(ref, q, &g2);
    REQUIRE(f1 == f2);
    REQUIRE(g1 == g2);
    inside += f1 >= 0.0f;
  }
  CHECK(inside > 0);
}

TEST_CASE("compile generic: random generic trees compiled directly match their snapshots bit for bit",
          "[animorph][compile]") {
  int bridgedPairs = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    int bridged = 0;
    const GenericTree c = seededGenericTree(seed, bridged);
    bridgedPairs += bridged;
    const AnimorphosisTiming timing = seededTiming();
    GenericProgramCompiler compiler(c);
    FieldProgram kept;
    for (double t : {0.2, 0.5, 0.61, 0.83, 1.0, 1.22, 1.5, 1.9}) {
      compiler.compile(timing, t, kept);
      requireSameProgram(kept, compileFieldProgram(instantiateGeneric(c, timing, t), 0.0), t);
    }
  }
  CHECK(bridgedPairs > 0);
}

namespace {

// Refills kept with C at t and checks it against a fresh compile of C at t (bit for bit); returns how
// the refill ended.
RefillOutcome refillAndCompare(GenericProgramCompiler& compiler, GenericProgramCompiler& fresh,
                               const AnimorphosisTiming& timing, double t, FieldProgram& kept) {
  const uint64_t structure = kept.structureIdentity(), identity = kept.identity();
  const RefillOutcome outcome = compiler.refill(timing, t, kept);
  FieldProgram ref;
  fresh.keepValues(false);  // the reference evaluates every node
  fresh.compile(timing, t, ref);
  INFO("refill outcome " << int(outcome));
  requireSameProgram(kept, ref, t);
  CHECK(kept.identity() != identity);
  // The structure's identity is kept exactly when the structure was.
  CHECK((kept.structureIdentity() == structure) == (outcome == RefillOutcome::Refilled));
  return outcome;
}

}  // namespace

TEST_CASE(
    "field program: a refill with new values equals a fresh compile (seeded animorphoses, the demo's C(t) at 24 times)",
    "[animorph][compile][refill]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  const AnimorphosisTiming timing = animorphosisTiming(*p);
  GenericProgramCompiler compiler(*c), fresh(*c);
  FieldProgram kept;
  int counts[3] = {0, 0, 0};  // by RefillOutcome
  // A scrub through the morph: 12 frames a twelfth of the interval apart, then 12 frames 1/30 s apart.
  const double a = kDemoMorphStartSec, b = kDemoMorphEndSec;
  std::vector<double> times;
  for (int k = 0; k < 12; ++k) times.push_back(a + (b - a) * (k + 0.5) / 12.0);
  for (int k = 0; k < 12; ++k) times.push_back(0.5 * (a + b) + k / 30.0);
  for (double t : times) ++counts[int(refillAndCompare(compiler, fresh, timing, t, kept))];
  INFO("demo: " << counts[0] << " refilled, " << counts[1] << " first, " << counts[2] << " structure changed");
  CHECK(counts[int(RefillOutcome::FirstCompile)] == 1);
  // Frames 1/30 s apart in the middle of the morph keep their structure (only values move).
  CHECK(counts[int(RefillOutcome::Refilled)] >= 11);

  // The polygonised meshes of a refilled program and of a fresh compile are the same, bit for bit.
  for (double t : {a + 0.31 * (b - a), 0.5 * (a + b) + 0.1}) {
    compiler.refill(timing, t, kept);
    FieldProgram ref;
    fresh.compile(timing, t, ref);
    auto m1 = polygonizePreviewProgram(kept, 40, 2, nullptr, nullptr);
    auto m2 = polygonizePreviewProgram(ref, 40, 2, nullptr, nullptr);
    REQUIRE(m1.ok());
    REQUIRE(m2.ok());
    CHECK(m1->mesh.triangleCount() > 100);
    CHECK(m1->mesh == m2->mesh);
  }

  // Seeded generic trees, one kept program each, refilled at times across the morph.
  int refilled = 0;
  for (unsigned seed = 11; seed <= 16; ++seed) {
    int bridged = 0;
    const GenericTree g = seededGenericTree(seed, bridged);
    const AnimorphosisTiming st = seededTiming();
    GenericProgramCompiler gc(g), gf(g);
    FieldProgram gk;
    for (double t : {0.2, 0.3, 0.61, 0.62, 0.83, 0.84, 1.0, 1.22, 1.23, 1.5, 1.9, 2.0})
      refilled += refillAndCompare(gc, gf, st, t, gk) == RefillOutcome::Refilled;
  }
  CHECK(refilled > 0);
}

TEST_CASE(
    "field program: a refill with kept values equals a fresh compile (the demo scrubbed forward, backward, by jumps, "
    "across B and C, a timing edit between frames)",
    "[animorph][compile][refill][kept]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  AnimorphosisTiming timing = animorphosisTiming(*p);
  GenericProgramCompiler compiler(*c), fresh(*c);
  FieldProgram kept;
  const double a = kDemoMorphStartSec, b = kDemoMorphEndSec, mid = 0.5 * (a + b);
  std::vector<double> times;
  for (int k = 0; k < 4; ++k) times.push_back(mid + k / 30.0);        // forward
  for (int k = 3; k >= 0; --k) times.push_back(mid - k / 30.0 - 0.2);  // backward
  for (double t : {a - 1.0, a - 0.5, a - 0.5, b + 0.5, b + 0.5 + 1 / 30.0, a + 0.1, b + 1.0, mid, a - 0.25})
    times.push_back(t);  // jumps across A (before t0), C (the morph) and B (after t1), a time twice
  size_t evaluated = 0;
  for (double t : times) {
    refillAndCompare(compiler, fresh, timing, t, kept);
    evaluated += compiler.lastEvaluatedNodes();
  }
  // A timing edit between frames (the source clip shifted and slowed): the clip times move, the
  // kept values whose inputs moved are evaluated again, the program still equals a fresh compile.
  timing.source.offsetSec += 0.37;
  timing.source.speed *= 0.8;
  for (double t : {mid, mid + 1 / 30.0, a - 0.5}) refillAndCompare(compiler, fresh, timing, t, kept);
  INFO(evaluated << " nodes evaluated over " << times.size() << " frames of " << compiler.nodeCount());
  CHECK(evaluated < (times.size() - 1) * compiler.nodeCount());
}

TEST_CASE("compile generic: scrubbing C(t) evaluates only the nodes whose inputs moved (counted)",
          "[animorph][compile][kept]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  const AnimorphosisTiming timing = animorphosisTiming(*p);
  GenericProgramCompiler compiler(*c);
  const size_t n = compiler.nodeCount();
  FieldProgram kept;
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  compiler.refill(timing, mid, kept);
  CHECK(compiler.lastEvaluatedNodes() == n);  // nothing kept yet
  compiler.refill(timing, mid, kept);
  CHECK(compiler.lastEvaluatedNodes() == 0);  // the same inputs: every value kept
  // Before the morph (A plays) and after it (B plays), a frame later: the nodes animated on the side
  // they read are evaluated, the nodes standing still (constant tracks) are not. (Inside the morph
  // the demo's global s(u) moves every node's blend: every node is evaluated.)
  for (double t : {kDemoMorphStartSec - 0.7, kDemoMorphEndSec + 0.5}) {
    compiler.refill(timing, t, kept);
    compiler.refill(timing, t + 1 / 30.0, kept);
    const size_t moved = compiler.lastEvaluatedNodes();
    INFO(moved << " of " << n << " nodes evaluated a frame after " << t << " s");
    CHECK(moved > 0);
    CHECK(moved < n / 4);
  }
  // With the values not kept, every node is evaluated every frame (the baseline).
  compiler.keepValues(false);
  compiler.refill(timing, mid, kept);
  compiler.refill(timing, mid, kept);
  CHECK(compiler.lastEvaluatedNodes() == n);
}

namespace {

// A small program with every kind of op: a map over two joined skeletal primitives, capsules, a
// constant, a blend of five or six operands (folded) and a remap. extra: one more capsule operand;
// join: whether the second skeletal primitive joins the first op (else a union of the two).
void buildSmall(FieldProgram& p, float r, float constant, bool extra, bool join) {
  p.threshold = 0.5f + 0.1f * r;
  p.beginMap(makeAffineMap(glm::vec3(r, 0.0f, 0.0f), glm::quat(1, 0, 0, 0), glm::vec3(1.0f + r)));
  SkeletalPrimitive s;
  s.skeleton.kind = SkeletonKind::Segment;
  s.skeleton.p1 = glm::vec3(0.0f, r, 0.0f);
  s.radius = 0.5f + r;
  p.addSkeletal(s, false, false);
  s.skeleton.p0 = glm::vec3(r, 0.0f, 0.0f);
  p.addSkeletal(s, join, false);
  if (!join) p.addOperator(OpCode::Max, 2);
  p.endMap();
  uint32_t operands = 1;
  for (int k = 0; k < (extra ? 3 : 2); ++k, ++operands)
    p.addCapsule({glm::vec3(float(k), r, 0.0f), glm::vec3(float(k), r + 1.0f, 0.0f), 0.3f + 0.1f * r}, false, false);
  p.addConstant(constant);
  ++operands;
  p.addConvolution(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f + r), 0.4f, 1.0f, 1e-3f, false);
  ++operands;
  p.addOperator(OpCode::Sum, operands);
  const float remap[2] = {1.0f + r, 0.8f};
  p.addOperator(OpCode::Remap, 1, remap, 2);
}

FieldProgram freshSmall(float r, float constant, bool extra, bool join) {
  FieldProgram p;
  buildSmall(p, r, constant, extra, join);
  p.finish();
  return p;
}

RefillOutcome refillSmall(FieldProgram& p, float r, float constant, bool extra, bool join) {
  p.beginRefill();
  buildSmall(p, r, constant, extra, join);
  const RefillOutcome outcome = p.finishRefill();
  requireSameProgram(p, freshSmall(r, constant, extra, join), r);
  return outcome;
}

}  // namespace

TEST_CASE("field program: a refill whose structure changed is refused and compiles fully",
          "[animorph][compile][refill]") {
  FieldProgram p;
  CHECK(refillSmall(p, 0.1f, 0.0f, false, true) == RefillOutcome::FirstCompile);
  REQUIRE(p.ops.size() > 6);
  const uint64_t structure = p.structureIdentity();
  CHECK(refillSmall(p, 0.2f, 0.0f, false, true) == RefillOutcome::Refilled);
  CHECK(p.structureIdentity() == structure);
  CHECK(refillSmall(p, 0.3f, 0.0f, true, true) == RefillOutcome::StructureChanged);  // one more operand
  CHECK(p.structureIdentity() != structure);
  CHECK(refillSmall(p, 0.4f, 0.0f, true, true) == RefillOutcome::Refilled);
  CHECK(refillSmall(p, 0.4f, 0.0f, true, false) == RefillOutcome::StructureChanged);  // not joined
  CHECK(refillSmall(p, 0.4f, 0.25f, true, false) == RefillOutcome::StructureChanged);  // a constant moved
  CHECK(refillSmall(p, 0.5f, 0.25f, true, false) == RefillOutcome::Refilled);
  // A fresh program seeded with the structure refills it.
  FieldProgram q;
  q.adoptStructure(p);
  CHECK(q.structureIdentity() == p.structureIdentity());
  CHECK(refillSmall(q, 0.7f, 0.25f, true, false) == RefillOutcome::Refilled);
  // reset() forgets the structure.
  p.reset();
  CHECK(refillSmall(p, 0.5f, 0.25f, true, false) == RefillOutcome::FirstCompile);
  // A malformed program keeps nothing to refill.
  FieldProgram bad;
  bad.addCapsule({glm::vec3(0.0f), glm::vec3(1.0f), 0.5f}, false, false);
  bad.addCapsule({glm::vec3(0.0f), glm::vec3(1.0f), 0.5f}, false, false);
  bad.finish();
  FieldProgram seeded;
  seeded.adoptStructure(bad);
  CHECK(seeded.structureIdentity() == 0);

  // The demo's C(t): the A side before the morph, then the middle (bridged pairs blend) and back.
  auto d = makeAnimorphosisDemoProject();
  REQUIRE(d.ok());
  auto c = projectGenericTree(*d);
  REQUIRE(c.ok());
  const AnimorphosisTiming timing = animorphosisTiming(*d);
  GenericProgramCompiler compiler(*c), fresh(*c);
  FieldProgram kept;
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  CHECK(refillAndCompare(compiler, fresh, timing, 0.0, kept) == RefillOutcome::FirstCompile);
  CHECK(refillAndCompare(compiler, fresh, timing, 0.1, kept) == RefillOutcome::Refilled);
  CHECK(refillAndCompare(compiler, fresh, timing, mid, kept) == RefillOutcome::StructureChanged);
  CHECK(refillAndCompare(compiler, fresh, timing, 0.0, kept) == RefillOutcome::StructureChanged);
}
