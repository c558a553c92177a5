#include "app/cli/bench/bench_demo_morph.h"

#include "demo/creature.h"
#include "demo/gear.h"
#include "core/io/gltf_export.h"
#include "core/project/new_morph_project.h"

namespace animorph::bench {

DemoMorphDir::DemoMorphDir() {
  if (!scratch.ok()) return;
  dir = scratch.path().string();
  const Character creature = makeCreatureCharacter(), gear = makeGearCharacter();
  exportGlb(creature, dir + "/creature.glb");
  exportGlb(gear, dir + "/gear.glb");
  NewMorphSettings ns;
  ns.alignScaleRatio = 4.0;
  ns.acceptPoorFit = true;  // measured whatever the fit: the bench times the bake, not the fit
  auto made = makeMorphProject(creature, "creature.glb", gear, "gear.glb", ns);
  if (made) project = made->project;
}

}  // namespace animorph::bench
