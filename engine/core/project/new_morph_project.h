#pragma once
// A complete morph project from two characters (what `animorph-cli new` and
// the demo write): both actors, automatic stand-ins, a default timeline with
// markers A..D, and the target aligned to the source: scaled by the ratio of
// their length units (Character::unit), then onto the source's bounding box
// when they still differ a lot in size or position.
#include <string>
#include <vector>

#include "core/project/project.h"
#include "core/rig/character.h"
#include "core/standin/fit_standin.h"
#include "core/util/result.h"

namespace animorph {

struct NewMorphSettings {
  double fps = 24.0;
  // Marker times (s): A, B, C, D and the end of the timeline.
  double aSec = 1.0, bSec = 2.0, cSec = 3.5, dSec = 4.5, endSec = 6.0;
  MorphMethod method = MorphMethod::Interpolation;
  FitSettings fit;
  // Align when the diagonals differ by more than this factor, or the centres
  // are further apart than this fraction of the source's diagonal.
  double alignScaleRatio = 1.5;
  double alignOffsetFraction = 0.5;
  // Aligning by a scale beyond this factor (either way), after the units'
  // ratio, is refused unless allowLargeRescale: no unit explains it.
  double maxRescaleWithoutConsent = 10.0;
  bool allowLargeRescale = false;
  // A poor stand-in fit (standin/fit_quality.h) is refused unless acceptPoorFit,
  // then it is a warning naming the bones.
  bool acceptPoorFit = false;
};

struct NewMorphProject {
  Project project;
  bool aligned = false;
  double scaleApplied = 1.0;  // uniform scale given to the target (the units' ratio included)
  std::vector<std::string> warnings;  // poor fits (accepted), large rescales (allowed): say them loudly
  FitReport sourceFit, targetFit;
  std::vector<std::string> messages;  // one line each, for the user (alignment, fit notes)
};

// sourceAsset / targetAsset are stored as the actors' asset paths (relative to
// the project file). Actor ids come from the file names. Errors (named by
// file): a stand-in could not be fitted, or fits poorly (naming the bones)
// and acceptPoorFit is off; alignment needs a scale beyond
// maxRescaleWithoutConsent that the units do not explain, and
// allowLargeRescale is off. messages say what was done ("target in
// centimetres, scaled by 0.01 to the source's metres").
Result<NewMorphProject> makeMorphProject(const Character& source, const std::string& sourceAsset,
                                         const Character& target, const std::string& targetAsset,
                                         const NewMorphSettings& settings = {});

}  // namespace animorph
