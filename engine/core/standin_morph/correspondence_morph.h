#pragma once
// The skeleton-correspondence morph (docs/morph.md, "Skeleton correspondence"):
// at blend w, the source's posed stand-in moves and resizes towards its image
// on the target (each segment's ends, radius and weight interpolated, by
// smoothstep(w), towards the target segment it maps to,
// standin_morph/skeleton_correspondence.h), and the
// target's grows out of its image on the source the same way. Both operands
// are posed at the same scene time, so both animations keep playing. The two
// in-between stand-ins are then combined by interpolation or space-time
// blending (buildMorphProgram); at w = 0 the source operand is the source's
// stand-in, at w = 1 the target operand the target's.
#include "core/standin_morph/morph_field.h"
#include "core/standin_morph/skeleton_correspondence.h"

namespace animorph {

// The source's stand-in at w on its way to the target (toTarget), or the
// target's at w on its way from the source (!toTarget). source and target:
// the posed stand-ins (MorphOperand without a tree).
MorphOperand correspondenceOperand(const SkeletonCorrespondence& c, const MorphOperand& source,
                                   const MorphOperand& target, float w, bool toTarget);

// The morph field at w: both in-between stand-ins combined by `combine`
// (Interpolation or SpaceTime; SkeletonCorrespondence reads as Interpolation).
FieldProgram buildCorrespondenceMorphProgram(const SkeletonCorrespondence& c, const MorphOperand& source,
                                             const MorphOperand& target, MorphMethod combine, float w,
                                             const SpaceTimeParams& spaceTime, float interpolationBound,
                                             bool colorProfiles = false);

}  // namespace animorph
