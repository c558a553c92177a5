#pragma once
// Where a morph's target goes relative to its source (animorph-cli new, Create > Morph...):
// first scaled by the ratio of the two characters' length units (Character::unit), then, when
// the sizes still differ a lot or the centres are far apart, onto the source's bounding box.
// A size difference the declared units leave that is close to a common unit's factor (glTF holding
// centimetre numbers, which it cannot declare) is taken as that unit and said so.
// Only the part of the scale that no unit explains can need the user's consent.
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
  // A resize beyond maxRescaleWithoutConsent within this factor (either way) of a common unit's
  // (centimetres, millimetres, inches, feet: 0.01, 0.001, 0.0254, 0.3048 m; the first that fits, in
  // that order) is taken as a file authored in that unit when that file declares metres or no unit:
  // the target is scaled by the unit's factor without consent, then aligned as usual. (Characters
  // differ in size too: the test characters by up to 1.9x; 10-20x, 200-500x, beyond 2000x stay refused.)
  double unitGuessTolerance = 2.0;
};

struct TargetAlignment {
  double unitScale = 1.0;     // target units -> source units (1 when the units agree), the guessed unit's included
  double guessedScale = 1.0;  // the part of unitScale a unit guessed from the sizes gives (1: no guess)
  double sizeRatio = 1.0;     // the resize the units leave (source diagonal / target's in source units)
  bool resize = false;        // sizeRatio is beyond alignScaleRatio (either way)
  bool move = false;          // the centres are far apart
  bool needsConsent = false;  // resize beyond maxRescaleWithoutConsent
  // The target's transform (relative to the source's frame) with everything applied:
  // scale unitScale x sizeRatio (when resize) and the translation onto the source's box.
  Transform transform;
  // "target in centimetres, scaled by 0.01 to the source's metres", or for a guessed unit "target is
  // 133x its partner (probably authored in centimetres): scaled by 0.01"; empty: same units
  std::string unitNote;
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
