#include "core/scene/transition_frame.h"

#include <algorithm>

namespace animorph {

TransitionFrame transitionFrame(const MorphRuntime& rt, bool expand, double timeSec, double u, bool reproject) {
  const MorphSetup& m = rt.setup;
  const MorphActorRuntime& a = expand ? rt.target : rt.source;
  TransitionFrame f;
  f.expand = expand;
  f.progress = float(std::clamp(u, 0.0, 1.0));
  f.perVertex = a.morph.weightMap.size() == a.vertexCount && m.weightMapShift > 0.0f;
  if (f.perVertex) {
    f.shift = std::min(m.weightMapShift, 0.999f);
    f.duration = 1.0f - f.shift;
    transitionEasingTable(m.easing, f.easingTable);
  } else {
    // The same call the CPU transition makes, for one vertex.
    std::vector<float> one;
    transitionAlphas(u, m.easing, {}, 0.0f, expand, 1, one);
    f.uniformAlpha = one[0];
  }

  // The CPU re-projects (transitionMesh) when asked, when reproject_from < 1
  // and when some vertex has alpha > 0; the shader checks the last per vertex.
  if (!reproject || !(m.projection.reprojectFrom < 1.0f)) return f;
  if (!f.perVertex && !(f.uniformAlpha > m.projection.reprojectFrom)) return f;  // nothing reaches it
  const MorphOperand posed = posedOperand(a, timeSec, -1.0);
  if (posed.segments.size() > kTransitionMaxSegments) {
    f.note = "actor '" + a.actor.id + "': " + std::to_string(posed.segments.size()) + " stand-in segments (the GPU " +
             "transition re-projects onto at most " + std::to_string(kTransitionMaxSegments) + ")";
    return f;
  }
  const FieldProgram prog = standinProgram(a.morph.standin.kind, a.morph.standin.sharpness, posed.segments);
  const TransitionSettings defaults;
  f.reproject = true;
  f.reprojectFrom = m.projection.reprojectFrom;
  f.maxIterations = defaults.reprojection.maxIterations;
  f.tolerance = defaults.reprojection.tolerance;
  f.maxStep = std::max(1e-6f, defaults.reprojection.maxStepRadii * medianSegmentRadius(posed.segments));
  f.threshold = prog.threshold;
  f.segments = posed.segments;
  const ConvolutionData& c = prog.convolution;
  for (size_t i = 0; i < c.size(); ++i) {
    TransitionPrimitive p;
    p.r0 = glm::vec4(c.bx[i], c.by[i], c.bz[i], c.length[i]);
    p.r1 = glm::vec4(c.ax[i], c.ay[i], c.az[i], c.weight[i]);
    p.r2 = glm::vec4(c.sharpness[i], c.cut2[i], 0.0f, 0.0f);
    f.primitives.push_back(p);
  }
  for (const SkeletalPrimitive& s : prog.skeletal) {
    TransitionPrimitive p;
    p.r0 = glm::vec4(s.skeleton.p0, s.radius);
    p.r1 = glm::vec4(s.skeleton.p1, s.intensity);
    p.r2 = glm::vec4(s.stiffness, 0.0f, 0.0f, 0.0f);
    f.primitives.push_back(p);
  }
  f.capsules = !prog.skeletal.empty();
  for (const FieldOp& op : prog.ops)
    if (op.code == OpCode::Prims) f.combineMax |= op.combineMax;
  return f;
}

}  // namespace animorph
