#pragma once
// The implicit morph between two posed stand-ins (docs/design.md §5, paper 1 eq. 3
// and 4), flattened into one FieldProgram that the polygonisers evaluate.
//  * interpolation: m = (1 - w) f1 + w f2. Both stand-ins share T, so this is
//    the sum of both stand-ins' primitives with weights scaled by 1 - w and w.
//  * space-time blending: g1 = f1 ^ (-tau), g2 = f2 ^ (tau - s), with
//    tau = s w, s the time scale; m = (g1 v g2) + disp(g1, g2, tau ^ (s - tau))
//    (Pasko's bounded blending with a0..a3, R-function ^ and v).
// At w <= 0 the program is f1's alone, at w >= 1 f2's alone, for both methods,
// so the morph starts and ends exactly on the stand-ins.
// Either side may be a BlobTree actor's own tree instead of a stand-in (its
// potential enters the interpolation through a Remap op scaling it by 1 - w
// or w); its threshold must be the stand-ins' T = 1.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/blobtree/blob_tree.h"
#include "core/field/field_program.h"
#include "core/math/transform.h"
#include "core/standin/standin.h"

namespace animorph {

// The one morph method enum (the GPU polygoniser's GpuField uses it too).
// SkeletonCorrespondence moves the source's stand-in into the target's along
// an automatic skeleton correspondence and combines the two in-between
// stand-ins by interpolation or space-time blending
// (standin_morph/correspondence_morph.h); buildMorphProgram reads it as Interpolation.
enum class MorphMethod : uint8_t { Interpolation, SpaceTime, SkeletonCorrespondence };

// Defaults chosen on the demo (creature -> gear, T = 1): both shapes stay
// visible and bridge in the middle; with a1 = a2 = a3 = 1 the transitional
// shapes are empty (the blend never reaches the threshold).
struct SpaceTimeParams {
  float timeScale = 1.0f;  // s: length of the morph along the time axis, in field units
  float a0 = 1.0f;         // blend amount (displacement height); 0: no bridge between the shapes
  float a1 = 5.0f;         // blend extent in the source's field units (larger: the source lingers)
  float a2 = 5.0f;         // blend extent in the target's field units (larger: the target appears early)
  float a3 = 0.02f;        // time bound's reach: smaller lets the blend act right after B and before C
  bool operator==(const SpaceTimeParams&) const = default;
};

// One side of the morph at one time: a posed stand-in, or (tree set) a
// BlobTree at treeTimeSec placed by transform.
struct MorphOperand {
  StandinKind kind = StandinKind::Convolution;
  float sharpness = 20.0f;
  std::vector<PosedSegment> segments;  // world space
  std::shared_ptr<const BlobTree> tree;
  double treeTimeSec = 0.0;
  Transform transform;  // tree space -> world
};

// Appends the operand to p as one operand with its potential multiplied by
// scale (stand-ins: their weights; trees: a Remap op when scale != 1).
// colorProfiles: a stand-in's coloured segments split into their colour samples
// (standin/standin_colors.h: the program of its colours, with the same field).
void appendMorphOperand(FieldProgram& p, const MorphOperand& op, float scale, bool colorProfiles = false);

// World box of the region where the operand can be inside (empty: nowhere).
Bounds morphOperandBounds(const MorphOperand& op);

// The morph field at blend value w in [0, 1] (w(t) of the morph's track).
// interpolationBound K > 1 (interpolation only): each side's potential p is
// first bounded to K T p / ((K - 1) T + p) (Remap op, field/operators.h),
// which keeps its surface p = T and caps it at K T, so the source's remnant
// (1 - w) h(p1) >= T shrinks to nothing by w = 1 - 1/K and the target grows
// from w = 1/K, instead of a thin remnant of the source living near its
// skeleton until the last frame before C. <= 1: the plain (unbounded) sum.
// colorProfiles: the program of the morph's colours (appendMorphOperand), for
// PolygonizeSettings::colorProgram: the same field, blended the same way.
FieldProgram buildMorphProgram(const MorphOperand& source, const MorphOperand& target, MorphMethod method, float w,
                               const SpaceTimeParams& spaceTime, float interpolationBound = 0.0f,
                               bool colorProfiles = false);

// "interpolation", "space_time", "skeleton_correspondence"
const char* morphMethodName(MorphMethod m);
// The method named name (as morphMethodName writes it); false when none is.
bool morphMethodFromName(const std::string& name, MorphMethod& out);

}  // namespace animorph
