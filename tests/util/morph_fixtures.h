#pragma once
// Shared, built-once fixtures for the stand-in / transition / morph tests:
// the demo characters and the creature -> gear morph, written to a temporary
// directory and prepared like a real project.
#include <memory>
#include <string>

#include "core/project/project.h"
#include "core/scene/morph_runtime.h"
#include "core/rig/character.h"

namespace animorph::test {

const Character& demoCreature();
const Character& demoGear();

// The demo morph: creature.glb -> gear.glb in a temporary directory (kept for
// the whole test run), as make-demo builds it (demo_morph.h).
struct DemoMorph {
  std::string dir;
  std::string projectPath;
  Project project;
  std::shared_ptr<const MorphRuntime> runtime;
};
const DemoMorph& demoMorph();

// tentacle.glb -> plate.glb in assetsDir (the shared assets), as `new` makes
// it (skeleton correspondence), built once; null when the files are not there
// (the caller skips, saying so). Throws when they are there but do not load.
const Project* tentaclePlateMorph(const std::string& assetsDir);

// Field value of a program at one point.
float fieldAt(const FieldProgram& p, const glm::vec3& x, glm::vec3* gradient = nullptr);

}  // namespace animorph::test
