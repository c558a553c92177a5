#include "core/standin_morph/morph_field.h"

#include <cmath>

#include "core/blobtree/compile.h"
#include "core/standin/standin_colors.h"

namespace animorph {

void appendMorphOperand(FieldProgram& p, const MorphOperand& op, float scale, bool colorProfiles) {
  if (!op.tree) {
    appendStandinOperand(p, op.kind, op.sharpness, colorProfiles ? splitSegmentsForColor(op.segments) : op.segments,
                         scale);
    return;
  }
  p.beginMap(makeAffineMap(op.transform.translation, op.transform.rotation, op.transform.scale));
  appendBlobTree(p, *op.tree, op.treeTimeSec);
  p.endMap();
  if (scale != 1.0f) {
    const float prm[2] = {scale, 0.0f};
    p.addOperator(OpCode::Remap, 1, prm, 2);
  }
}

Bounds morphOperandBounds(const MorphOperand& op) {
  if (!op.tree) return posedStandinBounds(op.segments, 0.0f);
  FieldProgram p;
  p.threshold = kStandinThreshold;
  appendMorphOperand(p, op, 1.0f);
  p.finish();
  return p.unbounded() ? Bounds{} : p.tightBounds(3);
}

const char* morphMethodName(MorphMethod m) {
  switch (m) {
    case MorphMethod::Interpolation: return "interpolation";
    case MorphMethod::SpaceTime: return "space_time";
    case MorphMethod::SkeletonCorrespondence: return "skeleton_correspondence";
  }
  return "interpolation";
}

bool morphMethodFromName(const std::string& name, MorphMethod& out) {
  for (MorphMethod m : {MorphMethod::Interpolation, MorphMethod::SpaceTime, MorphMethod::SkeletonCorrespondence})
    if (name == morphMethodName(m)) {
      out = m;
      return true;
    }
  return false;
}

FieldProgram buildMorphProgram(const MorphOperand& src, const MorphOperand& dst, MorphMethod method, float w,
                               const SpaceTimeParams& st, float bound, bool colorProfiles) {
  FieldProgram p;
  p.threshold = kStandinThreshold;
  const float T = p.threshold;
  if (method == MorphMethod::SkeletonCorrespondence) method = MorphMethod::Interpolation;
  if (!(w > 0.0f)) {
    appendMorphOperand(p, src, 1.0f, colorProfiles);
  } else if (!(w < 1.0f)) {
    appendMorphOperand(p, dst, 1.0f, colorProfiles);
  } else if (method == MorphMethod::Interpolation && bound > 1.0f) {
    for (const auto& [op, scale] : {std::pair{&src, 1.0f - w}, std::pair{&dst, w}}) {
      appendMorphOperand(p, *op, 1.0f, colorProfiles);
      const float prm[2] = {scale, bound};
      p.addOperator(OpCode::Remap, 1, prm, 2);
    }
    p.addOperator(OpCode::Sum, 2);
  } else if (method == MorphMethod::Interpolation) {
    appendMorphOperand(p, src, 1.0f - w, colorProfiles);
    appendMorphOperand(p, dst, w, colorProfiles);
    p.addOperator(OpCode::Sum, 2);
  } else {
    // Constants enter as potentials: a signed value s is the potential T + s.
    const float s = std::max(1e-6f, st.timeScale);
    const float tau = s * w;
    appendMorphOperand(p, src, 1.0f, colorProfiles);
    p.addConstant(T - tau);
    p.addOperator(OpCode::RIntersection, 2);
    appendMorphOperand(p, dst, 1.0f, colorProfiles);
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
