#include "core/animorphosis/evaluate_generic.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/animorphosis/param_blend.h"

namespace animorph {

float nodeS(const GenericTree& c, const GenericNode& n, const AnimorphosisTiming& timing, double timeSec) {
  const FloatTrack& s = n.sCurve >= 0 ? c.sCurves[size_t(n.sCurve)] : timing.globalS;
  return evaluateS(s, timing.u(timeSec));
}

namespace {

int subtreeNodes(const GenericNode& g) {
  int count = 1;
  for (const GenericNode& k : g.children) count += subtreeNodes(k);
  return count;
}

// Children of one node written in parallel from this many on (a wing membrane's patches, a
// part's fibres): each child's sub-tree is independent, its ids known from the sizes before it.
constexpr size_t kParallelChildren = 64;

struct Writer {
  const GenericTree& c;
  const AnimorphosisTiming& timing;
  double t, tA, tB;
  std::vector<float> sOfCurve;  // s(u) of each override curve, then of the global one (last)

  // Writes g's sub-tree into n with ids from `id` in pre-order; returns the id after the sub-tree.
  int node(const GenericNode& g, BlobNode& n, int id) {
    float s = sOfCurve[g.sCurve >= 0 ? size_t(g.sCurve) : sOfCurve.size() - 1];
    bool bridged = g.a.type != g.b.type;
    const BlobNode& named = s >= 1.0f ? g.b : g.a;
    NodeType type = s <= 0.0f ? g.a.type : s >= 1.0f ? g.b.type : bridged ? NodeType::HyperBlend : g.a.type;
    size_t params = nodeTypeInfo(type).params.size();
    if (n.type != type || n.params.size() != params) {
      n.type = type;
      n.params.assign(params, ParamValue{});
    }
    if (n.name != named.name) n.name = named.name;
    if (s <= 0.0f || s >= 1.0f) {
      const BlobNode& src = s <= 0.0f ? g.a : g.b;
      double ts = s <= 0.0f ? tA : tB;
      for (size_t i = 0; i < params; ++i) writeConstantParam(n.params[i], src.params[i], ts);
    } else if (bridged) {
      writeConstantFloat(n.params[0], (1.0f - s) * bridgeQ(g.a, tA) + s * bridgeQ(g.b, tB));
    } else {
      for (size_t i = 0; i < params; ++i) writeBlendedParam(n.params[i], g.a.params[i], g.b.params[i], tA, tB, s);
    }
    n.id = id++;
    if (n.children.size() != g.children.size()) n.children.resize(g.children.size());
    const size_t count = g.children.size();
    if (count < kParallelChildren) {
      for (size_t k = 0; k < count; ++k) id = node(g.children[k], n.children[k], id);
      return id;
    }
    std::vector<int> first(count);
    for (size_t k = 0; k < count; ++k) {
      first[k] = id;
      id += subtreeNodes(g.children[k]);
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 32), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t k = r.begin(); k < r.end(); ++k) node(g.children[k], n.children[k], first[k]);
    });
    return id;
  }
};

}  // namespace

float genericThreshold(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec) {
  double tA = timing.source.localTime(timeSec), tB = timing.target.localTime(timeSec);
  float s = evaluateS(timing.globalS, timing.u(timeSec));
  return s <= 0.0f   ? c.thresholdA.evaluate(tA)
         : s >= 1.0f ? c.thresholdB.evaluate(tB)
                     : (1.0f - s) * c.thresholdA.evaluate(tA) + s * c.thresholdB.evaluate(tB);
}

void updateGenericSnapshot(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec, BlobTree& snapshot) {
  double tA = timing.source.localTime(timeSec), tB = timing.target.localTime(timeSec);
  float s = evaluateS(timing.globalS, timing.u(timeSec));
  float threshold = genericThreshold(c, timing, timeSec);
  if (snapshot.threshold.keys().size() == 1 && !snapshot.threshold.driven()) snapshot.threshold.keys()[0] = {0.0, threshold};
  else snapshot.threshold = FloatTrack(threshold);
  Writer w{c, timing, timeSec, tA, tB, {}};
  // Each s curve evaluated once (as nodeS would for every node it drives).
  const double u = timing.u(timeSec);
  for (const FloatTrack& curve : c.sCurves) w.sOfCurve.push_back(evaluateS(curve, u));
  w.sOfCurve.push_back(s);
  w.node(c.root, snapshot.root, 1);
}

BlobTree instantiateGeneric(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec) {
  BlobTree tree;
  tree.root.params.clear();
  updateGenericSnapshot(c, timing, timeSec, tree);
  return tree;
}

FieldProgram compileGeneric(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec,
                            const CompileOptions& options) {
  return compileFieldProgram(instantiateGeneric(c, timing, timeSec), 0.0, options);
}

}  // namespace animorph
