// animorph-cli make-demo DIR: writes the procedural demo characters and a project.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/cli_command.h"
#include "demo/creature.h"
#include "demo/gear.h"
#include "doc/project_io.h"
#include "io/gltf_export.h"

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

  animorph::Project p;
  p.name = "demo";
  animorph::Actor walker;
  walker.id = "creature";
  walker.name = "Creature";
  walker.assetPath = "creature.glb";
  walker.clip = 0;
  animorph::Actor wheel;
  wheel.id = "gear";
  wheel.name = "Gear";
  wheel.assetPath = "gear.glb";
  wheel.clip = 0;
  wheel.transform.translation = {0.9f, 0.0f, 0.0f};
  p.actors = {walker, wheel};
  p.timeline.fps = 24.0;
  p.timeline.frameStart = 0;
  // Three walk cycles.
  p.timeline.frameEnd = static_cast<int>(std::lround(3.0 * creature.clips[0].durationSec * p.timeline.fps));
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
                     "  DIR/demo.animorph (both actors, the creature walking and the gear beside it,\n"
                     "  three walk cycles at 24 fps). DIR is created if needed; files are replaced.\n",
                     runMakeDemo);
