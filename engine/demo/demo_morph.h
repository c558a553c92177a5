#pragma once
// How the demo morph (creature -> gear) is made from the two demo characters:
// the settings `animorph-cli make-demo` writes resources/demo/demo.animorph with,
// and the tests' demo fixture uses.
#include "core/project/new_morph_project.h"

namespace animorph {

// Stand-ins fitted automatically, the default markers (A 1 s, B 2 s, C 3.5 s,
// D 4.5 s, end 6 s at 24 fps); the gear already stands where the creature does,
// so it keeps its own size (no alignment below a 4x size ratio). Skeleton
// correspondence combined with interpolation (the default for two rigs): the
// creature's limbs move and resize into the gear's spokes.
NewMorphSettings demoMorphSettings();

}  // namespace animorph
