#include "morph/morph_field.h"

#include <cmath>

namespace animorph {

const char* morphMethodName(MorphMethod m) { return m == MorphMethod::SpaceTime ? "space_time" : "interpolation"; }

FieldProgram buildMorphProgram(const MorphOperand& src, const MorphOperand& dst, MorphMethod method, float w,
                               const SpaceTimeParams& st) {
  FieldProgram p;
  p.threshold = kStandinThreshold;
  const float T = p.threshold;
  if (!(w > 0.0f)) {
    appendStandinOperand(p, src.kind, src.sharpness, src.segments, 1.0f);
  } else if (!(w < 1.0f)) {
    appendStandinOperand(p, dst.kind, dst.sharpness, dst.segments, 1.0f);
  } else if (method == MorphMethod::Interpolation) {
    appendStandinOperand(p, src.kind, src.sharpness, src.segments, 1.0f - w);
    appendStandinOperand(p, dst.kind, dst.sharpness, dst.segments, w);
    p.addOperator(OpCode::Sum, 2);
  } else {
    // Constants enter as potentials: a signed value s is the potential T + s.
    const float s = std::max(1e-6f, st.timeScale);
    const float tau = s * w;
    appendStandinOperand(p, src.kind, src.sharpness, src.segments, 1.0f);
    p.addConstant(T - tau);
    p.addOperator(OpCode::RIntersection, 2);
    appendStandinOperand(p, dst.kind, dst.sharpness, dst.segments, 1.0f);
    p.addConstant(T + tau - s);
    p.addOperator(OpCode::RIntersection, 2);
    const float bound = tau + (s - tau) - std::sqrt(tau * tau + (s - tau) * (s - tau));
    p.addConstant(T + bound);
    const float a[4] = {st.a0, std::max(1e-6f, st.a1), std::max(1e-6f, st.a2), std::max(1e-6f, st.a3)};
    p.addOperator(OpCode::BoundedBlend, 3, a, 4);
  }
  p.finish();
  return p;
}

}  // namespace animorph
