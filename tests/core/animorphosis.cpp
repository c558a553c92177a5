#include <catch2/catch.hpp>

#include <functional>
#include <random>

#include "core/animorphosis/correspondence_json.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/generic_tree.h"
#include "core/animorphosis/validate_correspondence.h"
#include "core/blobtree/compile.h"
#include "util/animorph_fixtures.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;
using Catch::Matchers::Contains;

namespace {

// Largest |f1 - f2| / max(|f1|, T) over n random points in [-2, 2]^3 and random times in [0, 2].
double largestRelativeDifference(const BlobTree& t1, const BlobTree& t2, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> x(-2.0f, 2.0f);
  std::uniform_real_distribution<double> time(0.0, 2.0);
  FieldEvaluator ev;
  double worst = 0.0;
  int perTime = 200;
  for (int done = 0; done < n; done += perTime) {
    double t = time(rng);
    FieldProgram p1 = compileFieldProgram(t1, t), p2 = compileFieldProgram(t2, t);
    for (int k = 0; k < perTime; ++k) {
      glm::vec3 p(x(rng), x(rng), x(rng));
      double f1 = ev.evaluatePoint(p1, p), f2 = ev.evaluatePoint(p2, p);
      worst = std::max(worst, std::abs(f1 - f2) / std::max(std::abs(f1), double(p1.threshold)));
    }
  }
  return worst;
}

GenericTree walkerToFlyer() {
  auto c = buildGenericTree(walkerTree(), flyerTree(), walkerToFlyerGraph());
  INFO(c.error());
  REQUIRE(c.ok());
  return *c;
}

}  // namespace

TEST_CASE("animorphosis: correspondence graph JSON round trip and bounded errors", "[animorph]") {
  CorrespondenceGraph g = walkerToFlyerGraph();
  g.links[3].artist = false;
  g.links[3].confidence = 0.25f;
  auto back = correspondenceFromJson(correspondenceToJson(g), "graph.json");
  REQUIRE(back.ok());
  CHECK(*back == g);

  nlohmann::json bad = correspondenceToJson(g);
  bad["links"][2]["confidence"] = 1.5;
  auto r = correspondenceFromJson(bad, "graph.json");
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.error(), Contains("graph.json") && Contains("link 2") && Contains("confidence"));

  bad = correspondenceToJson(g);
  bad["links"][1]["s"] = nlohmann::json{{"keys", {{{"t", 0.0}, {"v", 0.0}}, {{"t", 1.0}, {"v", 0.5}}}}};
  r = correspondenceFromJson(bad, "graph.json");
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.error(), Contains("link 1") && Contains("s(1) = 1"));

  bad = correspondenceToJson(g);
  bad["links"][0].erase("b");
  r = correspondenceFromJson(bad, "graph.json");
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.error(), Contains("link 0") && Contains("\"b\""));
}

TEST_CASE("animorphosis: links crossing the hierarchy are refused naming both nodes", "[animorph]") {
  BlobTree a = walkerTree(), b = flyerTree();
  REQUIRE(validateCorrespondence(a, b, walkerToFlyerGraph()).ok());

  SECTION("a link below a link leaves the linked sub-tree") {
    CorrespondenceGraph g;
    g.links.push_back({9, 112, {}, 1.0f, true});   // tail -> tail
    g.links.push_back({10, 103, {}, 1.0f, true});  // a tail bead -> the belly, outside the tail
    Status s = validateCorrespondence(a, b, g);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.error(), Contains("(id 10)") && Contains("'belly' (id 103)") && Contains("'tail' (id 9)") &&
                              Contains("must stay inside the linked sub-trees"));
  }
  SECTION("crossing links") {
    CorrespondenceGraph g;
    g.links.push_back({2, 109, {}, 1.0f, true});   // body -> legs frame
    g.links.push_back({6, 110, {}, 1.0f, true});   // a thigh (not in the body) -> a shin inside the legs frame
    Status s = validateCorrespondence(a, b, g);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.error(), Contains("'thighL' (id 6)") && Contains("'shinL' (id 110)") && Contains("cross"));
  }
  SECTION("a node linked to a node and its descendant") {
    CorrespondenceGraph g;
    g.links.push_back({2, 102, {}, 1.0f, true});
    g.links.push_back({2, 103, {}, 1.0f, true});
    Status s = validateCorrespondence(a, b, g);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.error(), Contains("'body' (id 2)") && Contains("'belly' (id 103)") && Contains("separate sub-trees"));
  }
  SECTION("a root linked to an inner node") {
    CorrespondenceGraph g;
    g.links.push_back({1, 102, {}, 1.0f, true});
    Status s = validateCorrespondence(a, b, g);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.error(), Contains("'walker' (id 1)") && Contains("'body' (id 102)") && Contains("root"));
  }
  SECTION("unknown ids and bad confidences") {
    CorrespondenceGraph g;
    g.links.push_back({2, 999, {}, 1.0f, true});
    CHECK_THAT(validateCorrespondence(a, b, g).error(), Contains("999") && Contains("target"));
    g.links[0] = {2, 102, {}, -0.5f, true};
    CHECK_THAT(validateCorrespondence(a, b, g).error(), Contains("'body' (id 2)") && Contains("confidence"));
  }
  SECTION("the generic tree refuses the same graph") {
    CorrespondenceGraph g;
    g.links.push_back({9, 112, {}, 1.0f, true});
    g.links.push_back({10, 103, {}, 1.0f, true});
    auto c = buildGenericTree(a, b, g);
    REQUIRE_FALSE(c.ok());
    CHECK_THAT(c.error(), Contains("(id 10)") && Contains("(id 103)"));
  }
}

TEST_CASE("animorphosis: splitting to a bijection leaves both fields unchanged", "[animorph]") {
  BlobTree a = walkerTree(), b = flyerTree();
  GenericTree c = walkerToFlyer();
  CHECK(c.splitCopies == 3);   // the body in two, the chest in two, the legs frame in two
  // The head, bead 115 and wingR have none; the chest (a point) and the membrane (a triangle) are of
  // kinds that do not meet, so each gets one: the chest shrinks where it is, the membrane grows.
  CHECK(c.nullPartners == 5);
  CHECK(c.sCurves.size() == 1);
  BlobTree a2 = genericSide(c, MorphSide::A), b2 = genericSide(c, MorphSide::B);
  CHECK(a2.root.subtreeSize() == b2.root.subtreeSize());
  CHECK(a2.root.subtreeSize() > a.root.subtreeSize());
  double ea = largestRelativeDifference(a, a2, 10000, 7);
  double eb = largestRelativeDifference(b, b2, 10000, 8);
  INFO("A' vs A: " << ea << ", B' vs B: " << eb);
  CHECK(ea <= 1e-6);
  CHECK(eb <= 1e-6);
}

TEST_CASE("animorphosis: s = 0 gives C(t) = A(t) and s = 1 gives C(t) = B(t), both animations playing", "[animorph]") {
  BlobTree a = walkerTree(), b = flyerTree();
  GenericTree c = walkerToFlyer();
  AnimorphosisTiming timing;
  timing.startSec = 2.0;
  timing.endSec = 4.0;
  timing.source = {0.0, 1.0, 1.0};   // the walk cycle loops every second
  timing.target = {1.5, 2.0, 0.5};   // the flight starts at 1.5 s, twice as fast, looping every 0.5 s
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> x(-2.0f, 2.0f);
  FieldEvaluator ev;
  double worstA = 0.0, worstB = 0.0;
  for (int k = 0; k < 40; ++k) {
    bool before = k % 2 == 0;
    double t = before ? 2.0 * k / 40.0 : 4.0 + k / 20.0;
    FieldProgram live = compileGeneric(c, timing, t);
    FieldProgram ref = before ? compileFieldProgram(a, timing.source.localTime(t))
                              : compileFieldProgram(b, timing.target.localTime(t));
    REQUIRE(live.threshold == ref.threshold);
    for (int i = 0; i < 250; ++i) {
      glm::vec3 p(x(rng), x(rng), x(rng));
      double fl = ev.evaluatePoint(live, p), fr = ev.evaluatePoint(ref, p);
      double e = std::abs(fl - fr) / std::max(std::abs(fr), double(ref.threshold));
      (before ? worstA : worstB) = std::max(before ? worstA : worstB, e);
    }
  }
  INFO("C vs A before t0: " << worstA << ", C vs B after t1: " << worstB);
  CHECK(worstA <= 1e-6);
  CHECK(worstB <= 1e-6);

  // In between, C differs from both, and the s override makes the wing grow faster than the rest.
  FieldProgram mid = compileGeneric(c, timing, 3.0);
  FieldProgram a3 = compileFieldProgram(a, timing.source.localTime(3.0));
  FieldProgram b3 = compileFieldProgram(b, timing.target.localTime(3.0));
  double dA = 0.0, dB = 0.0;
  for (int i = 0; i < 500; ++i) {
    glm::vec3 p(x(rng), x(rng), x(rng));
    dA = std::max(dA, double(std::abs(ev.evaluatePoint(mid, p) - ev.evaluatePoint(a3, p))));
    dB = std::max(dB, double(std::abs(ev.evaluatePoint(mid, p) - ev.evaluatePoint(b3, p))));
  }
  CHECK(dA > 0.05);
  CHECK(dB > 0.05);
  const GenericNode* wing = nullptr;
  for (const auto& ch : c.root.children)
    if (ch.sourceB == 105) wing = &ch;
  REQUIRE(wing != nullptr);
  CHECK(wing->sCurve == 0);
  CHECK(nodeS(c, *wing, timing, 2.5) > nodeS(c, c.root, timing, 2.5) + 0.1f);
  // The override drives the wing's whole sub-tree ...
  REQUIRE_FALSE(wing->children.empty());
  for (const auto& ch : wing->children) CHECK(ch.sCurve == 0);
  // ... unless a deeper link carries its own.
  CorrespondenceGraph g = walkerToFlyerGraph();
  g.links[4].sOverride = hermiteRampTrack(0.0f, 2.0f);  // chest -> left membrane
  auto deeper = buildGenericTree(a, b, g);
  REQUIRE(deeper.ok());
  CHECK(deeper->sCurves.size() == 2);
  for (const auto& ch : deeper->root.children)
    if (ch.sourceB == 105) {
      CHECK(ch.sCurve == 0);
      for (const auto& gc : ch.children) CHECK(gc.sCurve == 1);
    }
}

TEST_CASE("animorphosis: a blend bridged to a union is a hyper-blend in between", "[animorph]") {
  BlobTree a = treeOf(operatorNode(NodeType::Blend, 1, {pointNode(2, {-0.2f, 0, 0}, 0.6f), pointNode(3, {0.2f, 0, 0}, 0.6f)}));
  BlobTree b = treeOf(operatorNode(NodeType::Union, 1, {pointNode(2, {-0.2f, 0, 0}, 0.6f), pointNode(3, {0.2f, 0, 0}, 0.6f)}));
  CorrespondenceGraph g;
  g.links.push_back({2, 2, {}, 1.0f, true});
  g.links.push_back({3, 3, {}, 1.0f, true});
  auto c = buildGenericTree(a, b, g);
  REQUIRE(c.ok());
  AnimorphosisTiming timing;
  FieldEvaluator ev;
  glm::vec3 mid(0.0f);
  float fBlend = ev.evaluatePoint(compileFieldProgram(a, 0.0), mid);
  float fUnion = ev.evaluatePoint(compileFieldProgram(b, 0.0), mid);
  REQUIRE(fBlend > fUnion + 0.1f);
  float prev = fBlend + 1e-3f;
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    BlobTree snap = instantiateGeneric(*c, timing, t);
    float f = ev.evaluatePoint(compileFieldProgram(snap, 0.0), mid);
    if (t > 0.0 && t < 1.0) CHECK(snap.root.type == NodeType::HyperBlend);
    CHECK(f < prev);  // the blend's bulge between the two points sinks monotonically to the union's
    CHECK(f >= fUnion - 1e-5f);
    prev = f;
  }
  CHECK(prev == Approx(fUnion).margin(1e-6));
}

TEST_CASE("animorphosis: random splits of random creatures leave both fields unchanged", "[animorph]") {
  int built = 0, splits = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(seed);
    BlobTree a = randomCreature(rng, 60);
    std::unordered_map<int, int> idMap;
    BlobTree b = perturbedCopy(a, {0.5f, 0.0f, 0.0f}, 1.2f, rng, idMap, 0.05f);
    CorrespondenceGraph g;
    std::vector<int> ids;
    std::function<void(const BlobNode&)> collect = [&](const BlobNode& n) {
      ids.push_back(n.id);
      for (const auto& c : n.children) collect(c);
    };
    collect(a.root);
    for (int id : ids)
      if (id != a.root.id && rng() % 4 != 0) g.links.push_back({id, idMap.at(id), {}, 1.0f, true});
    // Extra links from a node to the partner of one of its siblings: splits on both sides.
    std::function<void(const BlobNode&)> extra = [&](const BlobNode& n) {
      for (size_t i = 0; i + 1 < n.children.size(); ++i)
        if (rng() % 3 == 0) {
          CorrespondenceGraph tried = g;
          tried.links.push_back({n.children[i].id, idMap.at(n.children[i + 1].id), {}, 1.0f, true});
          if (validateCorrespondence(a, b, tried).ok()) g = tried;
        }
      for (const auto& c : n.children) extra(c);
    };
    extra(a.root);
    REQUIRE(validateCorrespondence(a, b, g).ok());
    auto c = buildGenericTree(a, b, g);
    if (!c.ok()) {
      UNSCOPED_INFO("seed " << seed << ": " << c.error());
      // The only refusals allowed here are splits that would change a field.
      CHECK_THAT(c.error(), Contains("split") || Contains("distribute"));
      CHECK_THAT(c.error(), Contains("(id "));
      continue;
    }
    ++built;
    splits += c->splitCopies;
    double ea = largestRelativeDifference(a, genericSide(*c, MorphSide::A), 2000, seed);
    double eb = largestRelativeDifference(b, genericSide(*c, MorphSide::B), 2000, seed + 100);
    INFO("seed " << seed << ": " << c->splitCopies << " split copies, " << c->nullPartners << " null partners, A' "
                 << ea << ", B' " << eb);
    CHECK(ea <= 1e-6);
    CHECK(eb <= 1e-6);
    // And C(t) is A before the animorphosis, B after it.
    AnimorphosisTiming timing;
    timing.startSec = 0.5;
    timing.endSec = 1.5;
    FieldEvaluator ev;
    std::uniform_real_distribution<float> x(-2.0f, 2.0f);
    for (double t : {0.25, 1.75}) {
      FieldProgram live = compileGeneric(*c, timing, t);
      FieldProgram ref = compileFieldProgram(t < 1.0 ? a : b, t);
      double worst = 0.0;
      for (int i = 0; i < 300; ++i) {
        glm::vec3 p(x(rng), x(rng), x(rng));
        double fr = ev.evaluatePoint(ref, p);
        worst = std::max(worst, std::abs(ev.evaluatePoint(live, p) - fr) / std::max(std::abs(fr), double(ref.threshold)));
      }
      CHECK(worst <= 1e-6);
    }
  }
  INFO(built << " of 12 graphs built, " << splits << " split copies");
  CHECK(built == 12);
  CHECK(splits >= 10);
}

TEST_CASE("animorphosis: linked point, sphere, segment, cylinder and cone take the simplest common skeleton",
          "[animorph]") {
  auto prim = [](NodeType t, int id, glm::vec3 at) {
    BlobNode n = makeBlobNode(t, id);
    n.floatParam("radius") = FloatTrack(0.5f);
    if (paramIndex(t, "center") >= 0) n.vec3Param("center") = Vec3Track(at);
    if (paramIndex(t, "a") >= 0) {
      n.vec3Param("a") = Vec3Track(at);
      n.vec3Param("b") = Vec3Track(at + glm::vec3(0.0f, 0.6f, 0.1f));
    }
    if (paramIndex(t, "skeletonRadius") >= 0) n.floatParam("skeletonRadius") = FloatTrack(0.15f);
    if (t == NodeType::Cone) {
      n.floatParam("radiusA") = FloatTrack(0.2f);
      n.floatParam("radiusB") = FloatTrack(0.05f);
    }
    return n;
  };
  BlobTree a = treeOf(operatorNode(NodeType::Blend, 1, {prim(NodeType::Point, 2, {-1.2f, 0, 0}), prim(NodeType::Sphere, 3, {-0.4f, 0, 0}),
                                                        prim(NodeType::Segment, 4, {0.4f, 0, 0}), prim(NodeType::Cylinder, 5, {1.2f, 0, 0})}));
  a.root.children[0].vec3Param("center").setKey(1.0, {-1.2f, 0.3f, 0});
  BlobTree b = treeOf(operatorNode(NodeType::Blend, 1, {prim(NodeType::Segment, 2, {-1.1f, 0, 0.2f}), prim(NodeType::Point, 3, {-0.4f, 0.1f, 0}),
                                                        prim(NodeType::Cone, 4, {0.5f, 0, 0}), prim(NodeType::Cone, 5, {1.2f, -0.1f, 0})}));
  CorrespondenceGraph g;
  for (int id = 2; id <= 5; ++id) g.links.push_back({id, id, {}, 1.0f, true});
  auto c = buildGenericTree(a, b, g);
  INFO(c.error());
  REQUIRE(c.ok());
  CHECK(c->nullPartners == 0);
  REQUIRE(c->root.children.size() == 4);
  const NodeType expected[4] = {NodeType::Segment, NodeType::Sphere, NodeType::Cone, NodeType::Cone};
  for (size_t i = 0; i < 4; ++i) {
    CHECK(c->root.children[i].a.type == expected[i]);
    CHECK(c->root.children[i].b.type == expected[i]);
  }
  double ea = largestRelativeDifference(a, genericSide(*c, MorphSide::A), 4000, 31);
  double eb = largestRelativeDifference(b, genericSide(*c, MorphSide::B), 4000, 32);
  INFO("A' vs A " << ea << ", B' vs B " << eb);
  CHECK(ea <= 1e-6);
  CHECK(eb <= 1e-6);
  // Halfway, the point has stretched into half of the segment.
  AnimorphosisTiming timing;
  BlobTree mid = instantiateGeneric(*c, timing, 0.5);
  CHECK(mid.root.children[0].type == NodeType::Segment);
  glm::vec3 ma = mid.root.children[0].vec3Param("a").evaluate(0.0), mb = mid.root.children[0].vec3Param("b").evaluate(0.0);
  CHECK(glm::distance(ma, mb) == Approx(0.5 * glm::length(glm::vec3(0.0f, 0.6f, 0.1f))).margin(1e-5));

  // A ball and a segment have no common kind: one shrinks while the other grows.
  BlobTree ball = treeOf(operatorNode(NodeType::Blend, 1, {prim(NodeType::Sphere, 2, {0, 0, 0})}));
  BlobTree stick = treeOf(operatorNode(NodeType::Blend, 1, {prim(NodeType::Segment, 2, {0, 0, 0})}));
  CorrespondenceGraph one;
  one.links.push_back({2, 2, {}, 1.0f, true});
  auto d = buildGenericTree(ball, stick, one);
  REQUIRE(d.ok());
  CHECK(d->nullPartners == 2);
  CHECK(d->root.children.size() == 2);
}

TEST_CASE("animorphosis: a part with no partner grows out of the partner of its nearest linked sibling", "[animorph]") {
  GenericTree c = walkerToFlyer();
  // The flyer's right wing has no partner in the walker. Its nearest linked sibling is the flyer's
  // body, whose partner is the walker's body (belly and half the chest): the wing grows from there.
  const GenericNode* wing = nullptr;
  for (const auto& ch : c.root.children)
    if (ch.sourceB == 107) wing = &ch;
  REQUIRE(wing != nullptr);
  CHECK(wing->sourceA == -1);
  CHECK(wing->a.type == NodeType::Frame);
  CHECK(wing->a.vec3Param("translation").evaluate(0.0) == glm::vec3(0.0f));  // the identity frame
  REQUIRE(wing->children.size() == 1);
  const BlobNode& grown = wing->children[0].a;
  REQUIRE(grown.type == NodeType::Triangle);
  CHECK(grown.floatParam("intensity").evaluate(0.0) == 0.0f);
  glm::vec3 anchor = grown.vec3Param("a").evaluate(0.0);
  CHECK(grown.vec3Param("b").evaluate(0.0) == anchor);
  CHECK(grown.vec3Param("c").evaluate(0.0) == anchor);
  // The belly (0, 0, 0) and the chest (0.4, 0.1, 0) in the walker's body frame, at the origin at t = 0.
  CHECK(glm::distance(anchor, glm::vec3(0.2f, 0.05f, 0.0f)) < 1e-5f);

  // The walker's head has no partner in the flyer: it shrinks into the flyer's body (its nearest
  // linked sibling): the mean of its belly (0, 0, 0) and chest (0.45, 0.1, 0), moved by its frame (0, 0.1, 0).
  const GenericNode* head = nullptr;
  for (const auto& ch : c.root.children)
    if (ch.sourceA == 12) head = &ch;
  REQUIRE(head != nullptr);
  CHECK(head->b.floatParam("intensity").evaluate(0.0) == 0.0f);
  glm::vec3 into = head->b.vec3Param("center").evaluate(0.0);
  CHECK(glm::distance(into, glm::vec3(0.225f, 0.15f, 0.0f)) < 1e-5f);
}

TEST_CASE("animorphosis: a snapshot updated in place while scrubbing equals a fresh one", "[animorph]") {
  GenericTree c = walkerToFlyer();
  AnimorphosisTiming timing;
  timing.startSec = 1.0;
  timing.endSec = 2.0;
  timing.target = {0.0, 1.5, 0.5};
  BlobTree kept;
  // Forwards and backwards across t0 and t1, so bridged nodes change kind (blend, hyper-blend, union).
  for (double t : {0.5, 1.0, 1.2, 1.5, 1.99, 2.0, 2.4, 1.7, 1.1, 0.2, 1.6}) {
    updateGenericSnapshot(c, timing, t, kept);
    BlobTree fresh = instantiateGeneric(c, timing, t);
    INFO("t = " << t);
    CHECK(kept == fresh);
  }
  const BlobNode* tail = nullptr;
  for (const auto& ch : kept.root.children)
    if (ch.name == "tail") tail = &ch;
  REQUIRE(tail != nullptr);
  CHECK(tail->type == NodeType::HyperBlend);  // kept was last updated at t = 1.6, inside the interval
}

namespace {

// Walks a snapshot of C (taken before the interval, s = 0) beside A' in pre-order: ids 1..n in
// order, A's types, and every float or vector parameter at A's value at tA.
void checkSnapshotIsA(const BlobNode& snap, const BlobNode& a, double tA, int& nextId) {
  CHECK(snap.id == nextId++);
  REQUIRE(snap.type == a.type);
  REQUIRE(snap.params.size() == a.params.size());
  for (size_t i = 0; i < a.params.size(); ++i) {
    if (auto* f = std::get_if<FloatTrack>(&a.params[i])) CHECK(std::get<FloatTrack>(snap.params[i]).evaluate(0.0) == f->evaluate(tA));
    if (auto* v = std::get_if<Vec3Track>(&a.params[i])) CHECK(std::get<Vec3Track>(snap.params[i]).evaluate(0.0) == v->evaluate(tA));
  }
  REQUIRE(snap.children.size() == a.children.size());
  for (size_t k = 0; k < a.children.size(); ++k) checkSnapshotIsA(snap.children[k], a.children[k], tA, nextId);
}

}  // namespace

TEST_CASE("animorphosis: a node with many children is written with the ids and values of a walk in order",
          "[animorph]") {
  GenericTree c = walkerToFlyer();
  // 150 more copies of the root's sub-trees: wide enough that the children are written in parallel.
  const std::vector<GenericNode> original = c.root.children;
  for (int k = 0; k < 150; ++k) c.root.children.push_back(original[size_t(k) % original.size()]);
  AnimorphosisTiming timing;
  timing.startSec = 1.0;
  timing.endSec = 2.0;
  BlobTree kept;
  for (double t : {1.5, 0.5, 2.4, 0.25}) {
    updateGenericSnapshot(c, timing, t, kept);
    INFO("t = " << t);
    CHECK(kept == instantiateGeneric(c, timing, t));
    if (t < timing.startSec) {
      int nextId = 1;
      checkSnapshotIsA(kept.root, genericSide(c, MorphSide::A).root, timing.source.localTime(t), nextId);
      CHECK(size_t(nextId - 1) == c.size());
    }
  }
}
