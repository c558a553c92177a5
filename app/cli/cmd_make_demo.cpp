// animorph-cli make-demo DIR: writes the procedural demo characters and a project.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/cli/cli_command.h"
#include "demo/creature.h"
#include "demo/demo_morph.h"
#include "demo/gear.h"
#include "demo/rigged_figure.h"
#include "core/project/project_io.h"
#include "core/io/gltf_export.h"
#include "core/project/new_morph_project.h"

namespace {

namespace fs = std::filesystem;

int runMakeDemo(const std::vector<std::string>& args) {
  if (args.size() != 1 || args[0].empty() || args[0][0] == '-')
    return animorph::cli::fail("make-demo", "expected exactly one DIR (see animorph-cli make-demo --help)", 2);
  const fs::path dir = args[0];
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return animorph::cli::fail("make-demo", dir.string() + ": cannot create directory: " + ec.message());

  const animorph::Character creature = animorph::makeCreatureCharacter();
  const animorph::Character gear = animorph::makeGearCharacter();
  for (const auto& [name, character] : {std::pair{"creature.glb", &creature}, std::pair{"gear.glb", &gear}}) {
    const std::string path = (dir / name).string();
    if (auto s = animorph::exportGlb(*character, path); !s) return animorph::cli::fail("make-demo", s.error());
    std::printf("wrote %s (%zu triangles, %zu joints)\n", path.c_str(), character->totalTriangles(),
                character->totalJoints());
  }

  // A figure built like production rig exports, 60 units tall (helper bones,
  // node scales, face and finger bones): for trying stand-in fits on real rigs.
  {
    animorph::RiggedFigureOptions fo;
    fo.height = 60.0f;
    const animorph::Character figure = animorph::makeRiggedFigure(fo);
    const std::string path = (dir / "rigged_figure.glb").string();
    if (auto s = animorph::exportGlb(figure, path); !s) return animorph::cli::fail("make-demo", s.error());
    std::printf("wrote %s (%zu triangles, %zu joints)\n", path.c_str(), figure.totalTriangles(), figure.totalJoints());
  }

  // The creature morphs into the gear (demo_morph.h: skeleton correspondence).
  animorph::NewMorphSettings settings = animorph::demoMorphSettings();
  settings.acceptPoorFit = true;  // the demo is always written; a poor fit is printed as a warning
  auto made = animorph::makeMorphProject(creature, "creature.glb", gear, "gear.glb", settings);
  if (!made) return animorph::cli::fail("make-demo", made.error());
  animorph::Project p = std::move(made->project);
  p.name = "demo";
  for (const auto& m : made->messages) std::printf("%s\n", m.c_str());
  for (const auto& w : made->warnings) std::fprintf(stderr, "make-demo: WARNING: %s\n", w.c_str());
  const std::string projectPath = (dir / "demo.animorph").string();
  if (auto s = animorph::saveProject(p, projectPath); !s) return animorph::cli::fail("make-demo", s.error());
  std::printf("wrote %s (frames %d..%d at %g fps)\n", projectPath.c_str(), p.timeline.frameStart, p.timeline.frameEnd,
              p.timeline.fps);
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("make-demo", "write the procedural demo characters and project into DIR",
                     "usage: animorph-cli make-demo DIR\n"
                     "  Writes DIR/creature.glb (a skinned lizard-like quadruped with a 2 s walk cycle),\n"
                     "  DIR/gear.glb (a skinned gear with an axle hole and four windows, turning) and\n"
                     "  DIR/demo.animorph (the creature walks, collapses onto its stand-in from 1 s to\n"
                     "  2 s, morphs into the gear's stand-in by skeleton correspondence until 3.5 s,\n"
                     "  and the turning gear expands from it until 4.5 s; 6 s at 24 fps), and DIR/rigged_figure.glb (a humanoid built\n"
                     "  like production rig exports: 60 units tall, an armature node scaled 0.01 and\n"
                     "  turned 90 degrees, a scaled chest node, helper-bone chains, face and finger\n"
                     "  bones). DIR is created if needed; files are replaced.\n",
                     runMakeDemo);
