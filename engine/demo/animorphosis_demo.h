#pragma once
// The animorphosis demo project (resources/demo/animorphosis.animorph): the
// walking dinosaur turns into the flying dragon (dino_dragon.h) between
// kDemoMorphStartSec and kDemoMorphEndSec of an 8-second timeline at 24 fps,
// both clips looping through the transformation, with the artist's graph.
#include "core/project/project.h"
#include "core/util/result.h"

namespace animorph {

inline constexpr double kDemoMorphStartSec = 2.0;
inline constexpr double kDemoMorphEndSec = 6.0;

// The project, checked (checkAnimorphosis) before it is returned.
Result<Project> makeAnimorphosisDemoProject();

}  // namespace animorph
