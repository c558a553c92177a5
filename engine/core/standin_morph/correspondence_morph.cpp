#include "core/standin_morph/correspondence_morph.h"

#include <algorithm>

namespace animorph {

MorphOperand correspondenceOperand(const SkeletonCorrespondence& c, const MorphOperand& source,
                                   const MorphOperand& target, float w, bool toTarget) {
  const MorphOperand& own = toTarget ? source : target;
  const MorphOperand& other = toTarget ? target : source;
  const SkeletonChains& from = toTarget ? c.source : c.target;
  const SkeletonChains& onto = toTarget ? c.target : c.source;
  const std::vector<int>& match = toTarget ? c.sourceMatch : c.targetMatch;
  // k: how far this operand is from its own stand-in (0: itself, 1: its image).
  // Eased by smoothstep: the segments start and stop moving gently at B and C, where
  // the transitions hold the stand-ins still (measured: the largest frame-to-frame
  // volume change through B..C drops from 8.9 % to 6.1 % on the demo at 32^3, docs/morph.md).
  const float x = std::clamp(toTarget ? w : 1.0f - w, 0.0f, 1.0f);
  const float k = x * x * (3.0f - 2.0f * x);
  MorphOperand out = own;
  out.sharpness = own.sharpness + k * (other.sharpness - own.sharpness);
  if (k == 0.0f) return out;
  for (size_t i = 0; i < out.segments.size(); ++i) {
    if (from.chainOfSegment.size() <= i || from.chainOfSegment[i] < 0) continue;  // not in the rig: stays
    PosedSegment& s = out.segments[i];
    const SegmentImage img = segmentImage(from, int(i), onto, match, other.segments, s.radius);
    s.a += k * (img.a - s.a);
    s.b += k * (img.b - s.b);
    s.radius += k * (img.radius - s.radius);
    s.weightScale += k * (img.weightScale - s.weightScale);
  }
  return out;
}

FieldProgram buildCorrespondenceMorphProgram(const SkeletonCorrespondence& c, const MorphOperand& source,
                                             const MorphOperand& target, MorphMethod combine, float w,
                                             const SpaceTimeParams& spaceTime, float interpolationBound,
                                             bool colorProfiles) {
  const MorphMethod how = combine == MorphMethod::SpaceTime ? MorphMethod::SpaceTime : MorphMethod::Interpolation;
  if (source.tree || target.tree)
    return buildMorphProgram(source, target, how, w, spaceTime, interpolationBound, colorProfiles);
  const MorphOperand s = correspondenceOperand(c, source, target, w, true);
  const MorphOperand d = correspondenceOperand(c, source, target, w, false);
  return buildMorphProgram(s, d, how, w, spaceTime, interpolationBound, colorProfiles);
}

}  // namespace animorph
