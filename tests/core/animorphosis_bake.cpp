#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <numeric>
#include <map>
#include <random>
#include <set>

#include "core/animorphosis/bake_keys.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/generic_tree.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "util/animorph_fixtures.h"

using namespace animorph;
using namespace animorph::test;

namespace {

// The walker -> flyer graph without the bridged tails (they shrink and grow instead), so the baked
// tree has the live tree's node kinds at both ends.
CorrespondenceGraph graphWithoutBridges() {
  CorrespondenceGraph g = walkerToFlyerGraph();
  std::erase_if(g.links, [](const CorrespondenceLink& l) { return l.nodeA >= 9 && l.nodeA <= 11; });
  return g;
}

AnimorphosisTiming bakeTiming() {
  AnimorphosisTiming timing;
  timing.startSec = 1.0;
  timing.endSec = 3.0;
  timing.source = {0.0, 1.0, 0.0};
  timing.target = {1.0, 1.0, 0.0};
  return timing;
}

// Largest |f_baked - f_live| / max(|f_live|, T) over random points at time t.
double fieldGap(const BlobTree& baked, const GenericTree& c, const AnimorphosisTiming& timing, double t, std::mt19937& rng) {
  std::uniform_real_distribution<float> x(-2.0f, 2.0f);
  FieldEvaluator ev;
  FieldProgram pb = compileFieldProgram(baked, t), pl = compileGeneric(c, timing, t);
  double worst = std::abs(double(pb.threshold) - pl.threshold) / pl.threshold;
  for (int i = 0; i < 300; ++i) {
    glm::vec3 p(x(rng), x(rng), x(rng));
    double fb = ev.evaluatePoint(pb, p), fl = ev.evaluatePoint(pl, p);
    worst = std::max(worst, std::abs(fb - fl) / std::max(std::abs(fl), double(pl.threshold)));
  }
  return worst;
}

}  // namespace

TEST_CASE("animorphosis: the key-frame bake equals the live C at every key, with at most nA + nB + ns keys",
          "[animorph]") {
  BlobTree a = walkerTree(), b = flyerTree();
  auto c = buildGenericTree(a, b, graphWithoutBridges());
  REQUIRE(c.ok());
  AnimorphosisTiming timing = bakeTiming();
  BakedAnimorphosis baked = bakeKeyframes(*c, timing);
  REQUIRE(validateBlobTree(baked.tree).ok());
  const BakeKeysReport& r = baked.report;
  INFO("channels " << r.parameters << ", keys " << r.keys << ", most keys " << r.mostKeys << " (bound "
                   << r.mostKeysBound << "), largest deviation " << r.largestDeviation << " at "
                   << r.largestDeviationAt);
  CHECK(r.withinBound);
  CHECK(r.mostKeys <= r.mostKeysBound);
  CHECK(r.mostKeys >= 4);  // animated parameters do get keys from A, B and s
  CHECK(baked.tree.root.subtreeSize() == c->size());

  // Every channel, at each of its own keys, holds the live C's value of that parameter.
  std::map<double, std::vector<const BlobNode*>> liveNodes;
  std::map<double, BlobTree> liveTrees;
  auto liveNode = [&](double t, int id) {
    if (!liveTrees.count(t)) {
      liveTrees[t] = instantiateGeneric(*c, timing, t);
      std::vector<const BlobNode*>& v = liveNodes[t];
      v.assign(size_t(c->size()) + 1, nullptr);
      std::function<void(const BlobNode&)> index = [&](const BlobNode& n) {
        v[size_t(n.id)] = &n;
        for (const auto& ch : n.children) index(ch);
      };
      index(liveTrees[t].root);
    }
    return liveNodes[t][size_t(id)];
  };
  double keyGap = 0.0;
  size_t keysChecked = 0;
  std::set<double> keyTimes;
  auto inside = [&](double t) { return t >= timing.startSec && t <= timing.endSec; };
  std::function<void(const BlobNode&)> check = [&](const BlobNode& n) {
    for (size_t i = 0; i < n.params.size(); ++i) {
      const ParamValue& p = n.params[i];
      if (auto* f = std::get_if<FloatTrack>(&p)) {
        for (const auto& k : f->keys())
          if (inside(k.timeSec)) {
            keyGap = std::max(keyGap, double(std::abs(k.value - std::get<FloatTrack>(liveNode(k.timeSec, n.id)->params[i]).evaluate(0.0))));
            ++keysChecked;
            keyTimes.insert(k.timeSec);
          }
      } else if (auto* v = std::get_if<Vec3Track>(&p)) {
        for (const auto& k : v->keys())
          if (inside(k.timeSec)) {
            keyGap = std::max(keyGap, double(glm::distance(k.value, std::get<Vec3Track>(liveNode(k.timeSec, n.id)->params[i]).evaluate(0.0))));
            ++keysChecked;
            keyTimes.insert(k.timeSec);
          }
      } else if (auto* q = std::get_if<QuatTrack>(&p)) {
        for (const auto& k : q->keys())
          if (inside(k.timeSec)) {
            glm::quat l = std::get<QuatTrack>(liveNode(k.timeSec, n.id)->params[i]).evaluate(0.0);
            keyGap = std::max(keyGap, 1.0 - std::abs(double(glm::dot(k.value, l))));
            ++keysChecked;
            keyTimes.insert(k.timeSec);
          }
      }
    }
    for (const auto& ch : n.children) check(ch);
  };
  check(baked.tree.root);
  INFO(keysChecked << " keys checked at " << keyTimes.size() << " times; largest gap " << keyGap);
  CHECK(keysChecked >= 60);
  CHECK(keyTimes.size() >= 5);
  CHECK(keyGap <= 1e-6);

  // Between keys: within the stated tolerance, parameters and field alike.
  std::mt19937 rng(5);
  std::vector<double> times(keyTimes.begin(), keyTimes.end());
  double between = 0.0;
  for (size_t i = 0; i + 1 < times.size(); ++i)
    between = std::max(between, fieldGap(baked.tree, *c, timing, 0.5 * (times[i] + times[i + 1]), rng));
  INFO("field gap between keys: " << between);
  CHECK(r.largestDeviation <= 0.02);  // measured: 0.018 rad, the body frame rotation
  CHECK(between <= 0.05);  // measured: 0.034 of max(|f|, T)

  // Outside the interval the baked tree holds C(t0) and C(t1): A(t0) and B(t1).
  CHECK(fieldGap(baked.tree, *c, timing, timing.startSec, rng) <= 1e-5);
  CHECK(fieldGap(baked.tree, *c, timing, timing.endSec, rng) <= 1e-5);
}

TEST_CASE("animorphosis: the bake of a parameter linear in time under a linear s is exact between keys",
          "[animorph]") {
  // p_A linear, p_B constant, s(u) = u: p_C is quadratic, which cubic Hermite keys with
  // product-rule slopes reproduce exactly.
  BlobTree a, b;
  a.root = makeBlobNode(NodeType::Point, 1);
  a.root.floatParam("radius") = FloatTrack(0.5f);
  a.root.floatParam("radius").setKey(4.0, 1.5f, KeyInterp::Linear);
  a.root.floatParam("radius").keys().front().interp = KeyInterp::Linear;
  b.root = makeBlobNode(NodeType::Point, 1);
  b.root.floatParam("radius") = FloatTrack(0.8f);
  CorrespondenceGraph g;
  g.links.push_back({1, 1, {}, 1.0f, true});
  auto c = buildGenericTree(a, b, g);
  REQUIRE(c.ok());
  AnimorphosisTiming timing;
  timing.startSec = 0.0;
  timing.endSec = 4.0;
  timing.globalS = FloatTrack();
  timing.globalS.clearKeys();
  timing.globalS.setKey(0.0, 0.0f, KeyInterp::Linear);
  timing.globalS.setKey(1.0, 1.0f, KeyInterp::Linear);
  BakedAnimorphosis baked = bakeKeyframes(*c, timing);
  const FloatTrack& r = baked.tree.root.floatParam("radius");
  CHECK(r.keys().size() == 2);  // nA = 2, nB = 1, ns = 2: keys at 0 and 4 only
  for (double t = 0.0; t <= 4.0; t += 0.25) {
    double u = t / 4.0, pa = 0.5 + 0.25 * t, pc = (1.0 - u) * pa + u * 0.8;
    CHECK(r.evaluate(t) == Approx(pc).margin(1e-5));
  }
  CHECK(baked.report.largestDeviation < 1e-5);
}
