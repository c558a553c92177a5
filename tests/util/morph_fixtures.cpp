#include "util/morph_fixtures.h"

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "demo/creature.h"
#include "demo/demo_morph.h"
#include "demo/gear.h"
#include "core/project/project_io.h"
#include "core/io/gltf_export.h"
#include "core/io/gltf_import.h"
#include "core/project/new_morph_project.h"

namespace animorph::test {

const Character& demoCreature() {
  static const Character c = makeCreatureCharacter();
  return c;
}

const Character& demoGear() {
  static const Character c = makeGearCharacter();
  return c;
}

namespace {

DemoMorph buildDemoMorph() {
  DemoMorph d;
  std::string tmpl = (std::filesystem::temp_directory_path() / "animorph-morph-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
  d.dir = tmpl;
  if (!exportGlb(demoCreature(), d.dir + "/creature.glb") || !exportGlb(demoGear(), d.dir + "/gear.glb"))
    throw std::runtime_error("cannot write the demo characters");
  const NewMorphSettings s = demoMorphSettings();
  auto made = makeMorphProject(demoCreature(), "creature.glb", demoGear(), "gear.glb", s);
  if (!made) throw std::runtime_error(made.error());
  d.project = made->project;
  d.projectPath = d.dir + "/demo.animorph";
  if (!saveProject(d.project, d.projectPath)) throw std::runtime_error("cannot save the demo project");
  AssetCache assets;
  auto rt = prepareMorph(d.project, d.dir, assets);
  if (!rt) throw std::runtime_error(rt.error());
  d.runtime = *rt;
  return d;
}

struct Cleanup {
  std::string dir;
  ~Cleanup() {
    std::error_code ec;
    if (!dir.empty()) std::filesystem::remove_all(dir, ec);
  }
};

}  // namespace

const DemoMorph& demoMorph() {
  static const DemoMorph d = buildDemoMorph();
  static Cleanup cleanup{d.dir};
  return d;
}

const Project* tentaclePlateMorph(const std::string& dir) {
  static const std::optional<Project> made = [&]() -> std::optional<Project> {
    if (!std::filesystem::exists(dir + "/tentacle.glb") || !std::filesystem::exists(dir + "/plate.glb"))
      return std::nullopt;
    auto tentacle = importGltf(dir + "/tentacle.glb");
    auto plate = importGltf(dir + "/plate.glb");
    if (!tentacle || !plate) throw std::runtime_error(dir + ": tentacle.glb or plate.glb does not load");
    NewMorphSettings ns;
    ns.method = MorphMethod::SkeletonCorrespondence;
    auto m = makeMorphProject(*tentacle, "tentacle.glb", *plate, "plate.glb", ns);
    if (!m) throw std::runtime_error(m.error());
    return m->project;
  }();
  return made ? &*made : nullptr;
}

float fieldAt(const FieldProgram& p, const glm::vec3& x, glm::vec3* gradient) {
  FieldEvaluator e;
  return e.evaluatePoint(p, x, gradient);
}

}  // namespace animorph::test
