#pragma once
// Where a morph's target goes relative to its source (animorph-cli new, Create > Morph...):
// first scaled by the ratio of the two characters' length units (Character::unit), then, when
// the sizes still differ a lot or the centres are far apart, onto the source's bounding box.
// Only the part of the scale that the units do not explain can need the user's consent.
#include <string>

#include "core/math/transform.h"
#include "core/rig/character.h"

namespace animorph {

struct AlignmentSettings {
  // Resize when the diagonals (in the source's units) differ by more than this factor; move
  // when the centres are further apart than this fraction of the source's diagonal.
  double alignScaleRatio = 1.5;
  double alignOffsetFraction = 0.5;
  // A resize beyond this factor (either way) that no unit explains needs consent.
  double maxRescaleWithoutConsent = 10.0;
};

struct TargetAlignment {
  double unitScale = 1.0;     // target units -> source units (1 when the units agree)
  double sizeRatio = 1.0;     // the resize the units leave (source diagonal / target's in source units)
  bool resize = false;        // sizeRatio is beyond alignScaleRatio (either way)
  bool move = false;          // the centres are far apart
  bool needsConsent = false;  // resize beyond maxRescaleWithoutConsent
  // The target's transform (relative to the source's frame) with everything applied:
  // scale unitScale x sizeRatio (when resize) and the translation onto the source's box.
  Transform transform;
  std::string unitNote;  // "target in centimetres, scaled by 0.01 to the source's metres"; empty: same units
  std::string sizeNote;  // what the resize is and why it needs consent; empty when it does not
  bool changes() const { return unitScale != 1.0 || resize || move; }
};

// The alignment of target onto source, both posed at rest (standin/character_pose.h's bounds).
// Characters without geometry get only the unit scale.
TargetAlignment alignTargetToSource(const Character& source, const Character& target, const AlignmentSettings& s = {});

// The transform of a target actor that keeps only the unit scale (no resize or move): what the
// editor applies when the user declines an unexplained resize.
Transform unitsOnly(const TargetAlignment& a);

}  // namespace animorph
