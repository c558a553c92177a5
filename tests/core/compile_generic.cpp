#include <catch2/catch.hpp>

#include <cstring>
#include <functional>
#include <random>

#include "core/animorphosis/compile_generic.h"
#include "core/animorphosis/evaluate_generic.h"
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
    std::mt19937 rng(seed);
    BlobTree a = randomCreature(rng, 80);
    std::unordered_map<int, int> idMap;
    BlobTree b = perturbedCopy(a, {0.4f, 0.1f, 0.0f}, 1.3f, rng, idMap, 0.05f);
    // Some blends of B become unions: their pairs are bridged (a hyper-blend in between).
    int bridged = 0;
    std::function<void(BlobNode&)> bridge = [&](BlobNode& n) {
      if (n.type == NodeType::Blend && &n != &b.root && rng() % 3 == 0) {
        n.type = NodeType::Union;
        ++bridged;
      }
      for (BlobNode& k : n.children) bridge(k);
    };
    bridge(b.root);
    // Most nodes linked to their copies (the rest get null partners), some with their own s(u).
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
    bridgedPairs += bridged;
    AnimorphosisTiming timing;
    timing.startSec = 0.5;
    timing.endSec = 1.5;
    timing.target.speed = 1.5;
    GenericProgramCompiler compiler(*c);
    FieldProgram kept;
    for (double t : {0.2, 0.5, 0.61, 0.83, 1.0, 1.22, 1.5, 1.9}) {
      compiler.compile(timing, t, kept);
      requireSameProgram(kept, compileFieldProgram(instantiateGeneric(*c, timing, t), 0.0), t);
    }
  }
  CHECK(bridgedPairs > 0);
}
