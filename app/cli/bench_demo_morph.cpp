#include "cli/bench_demo_morph.h"

#include <cstdlib>
#include <filesystem>

#include "demo/creature.h"
#include "demo/gear.h"
#include "io/gltf_export.h"
#include "morph/new_morph_project.h"

namespace animorph::bench {

DemoMorphDir::DemoMorphDir() {
  std::string tmpl = (std::filesystem::temp_directory_path() / "animorph-bench-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) return;
  dir = tmpl;
  const Character creature = makeCreatureCharacter(), gear = makeGearCharacter();
  exportGlb(creature, dir + "/creature.glb");
  exportGlb(gear, dir + "/gear.glb");
  NewMorphSettings ns;
  ns.alignScaleRatio = 4.0;
  ns.acceptPoorFit = true;  // measured whatever the fit: the bench times the bake, not the fit
  auto made = makeMorphProject(creature, "creature.glb", gear, "gear.glb", ns);
  if (made) project = made->project;
}

DemoMorphDir::~DemoMorphDir() {
  if (dir.empty()) return;
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace animorph::bench
