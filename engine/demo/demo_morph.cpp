#include "demo/demo_morph.h"

namespace animorph {

NewMorphSettings demoMorphSettings() {
  NewMorphSettings s;
  s.alignScaleRatio = 4.0;
  s.method = MorphMethod::SkeletonCorrespondence;
  return s;
}

}  // namespace animorph
