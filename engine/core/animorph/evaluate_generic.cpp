#include "animorph/evaluate_generic.h"

#include "animorph/param_blend.h"

namespace animorph {

float nodeS(const GenericTree& c, const GenericNode& n, const AnimorphosisTiming& timing, double timeSec) {
  const FloatTrack& s = n.sCurve >= 0 ? c.sCurves[size_t(n.sCurve)] : timing.globalS;
  return evaluateS(s, timing.u(timeSec));
}

namespace {

struct Instantiator {
  const GenericTree& c;
  const AnimorphosisTiming& timing;
  double t, tA, tB;
  int nextId = 1;

  BlobNode node(const GenericNode& g) {
    float s = nodeS(c, g, timing, t);
    BlobNode n;
    if (s <= 0.0f || s >= 1.0f) {
      const BlobNode& src = s <= 0.0f ? g.a : g.b;
      double ts = s <= 0.0f ? tA : tB;
      n.type = src.type;
      n.name = src.name;
      n.params.reserve(src.params.size());
      for (const ParamValue& p : src.params) n.params.push_back(constantParam(p, ts));
    } else if (g.a.type != g.b.type) {
      n = makeBlobNode(NodeType::HyperBlend, 0, g.a.name);
      n.floatParam("q") = FloatTrack((1.0f - s) * bridgeQ(g.a, tA) + s * bridgeQ(g.b, tB));
    } else {
      n.type = g.a.type;
      n.name = g.a.name;
      n.params.reserve(g.a.params.size());
      for (size_t i = 0; i < g.a.params.size(); ++i) n.params.push_back(blendParam(g.a.params[i], g.b.params[i], tA, tB, s));
    }
    n.id = nextId++;
    n.children.reserve(g.children.size());
    for (const GenericNode& ch : g.children) n.children.push_back(node(ch));
    return n;
  }
};

}  // namespace

BlobTree instantiateGeneric(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec) {
  double tA = timing.source.localTime(timeSec), tB = timing.target.localTime(timeSec);
  Instantiator in{c, timing, timeSec, tA, tB};
  BlobTree tree;
  float s = evaluateS(timing.globalS, timing.u(timeSec));
  tree.threshold = FloatTrack((1.0f - s) * c.thresholdA.evaluate(tA) + s * c.thresholdB.evaluate(tB));
  if (s <= 0.0f) tree.threshold = FloatTrack(c.thresholdA.evaluate(tA));
  if (s >= 1.0f) tree.threshold = FloatTrack(c.thresholdB.evaluate(tB));
  tree.root = in.node(c.root);
  return tree;
}

FieldProgram compileGeneric(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec,
                            const CompileOptions& options) {
  return compileFieldProgram(instantiateGeneric(c, timing, timeSec), 0.0, options);
}

}  // namespace animorph
