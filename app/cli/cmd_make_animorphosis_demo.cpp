// animorph-cli make-animorphosis-demo DIR [--scenes]: writes the project in
// which the dinosaur turns into the dragon (and, with --scenes, both creatures).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "core/blobtree/blob_tree_json.h"
#include "app/cli/cli_command.h"
#include "app/cli/demo_files.h"
#include "demo/animorphosis_demo.h"
#include "demo/dino_dragon.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"

namespace {

using namespace animorph;
using nlohmann::json;
using cli::writeCompact;

int makeAnimorphosisDemo(const std::vector<std::string>& args) {
  const char* cmd = "make-animorphosis-demo";
  std::vector<std::string> dirs;
  bool scenes = false;
  for (const std::string& a : args) {
    if (a == "--scenes")
      scenes = true;
    else if (!a.empty() && a[0] == '-')
      return cli::fail(cmd, "unknown option " + a, 2);
    else
      dirs.push_back(a);
  }
  std::filesystem::path dir;
  if (!cli::outputDirectory(cmd, dirs, dir)) return dirs.size() != 1 ? 2 : 1;
  auto project = makeAnimorphosisDemoProject();
  if (!project) return cli::fail(cmd, "internal: " + project.error(), 3);
  const char* files[2] = {"dinosaur.json", "dragon.json"};
  for (int k = 0; k < (scenes ? 2 : 0); ++k) {
    const BlobTree& tree = project->actors[size_t(k)].blobTree;
    std::filesystem::path path = dir / files[k];
    if (auto s = writeCompact(blobTreeSceneToJson(tree), path); !s) return cli::fail(cmd, s.error());
    std::printf("wrote %s (%zu nodes, loops over %g s, %ju bytes)\n", path.string().c_str(), tree.root.subtreeSize(),
                k == 0 ? kDinosaurLoopSec : kDragonLoopSec, std::uintmax_t(std::filesystem::file_size(path)));
  }
  auto generic = projectGenericTree(*project);
  if (!generic) return cli::fail(cmd, "internal: " + generic.error(), 3);
  std::filesystem::path path = dir / "animorphosis.animorph";
  json j = json::parse(projectToJson(*project));
  if (auto s = writeCompact(std::move(j), path); !s) return cli::fail(cmd, s.error());
  size_t overrides = 0;
  for (const auto& l : project->animorphosis.graph.links) overrides += l.sOverride ? 1 : 0;
  std::printf("wrote %s (%zu links, %zu with their own s; generic tree of %zu nodes; frames %g..%g of %d at %g fps; "
              "%ju bytes)\n",
              path.string().c_str(), project->animorphosis.graph.links.size(), overrides, generic->size(),
              project->timeline.secToFrame(kDemoMorphStartSec), project->timeline.secToFrame(kDemoMorphEndSec),
              project->timeline.frameEnd, project->timeline.fps, std::uintmax_t(std::filesystem::file_size(path)));
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("make-animorphosis-demo", "write the dinosaur -> dragon animorphosis demo (scenes and project)",
                     "usage: animorph-cli make-animorphosis-demo DIR [--scenes]\n"
                     "  Writes DIR/animorphosis.animorph: a project in which a walking biped dinosaur\n"
                     "  turns into a flying dragon between 2 s and 6 s, both clips playing, with an\n"
                     "  artist's graph (body, legs and head linked, the wings unlinked so they grow out\n"
                     "  of the back) and s overrides (wings and legs faster, the height held down for the\n"
                     "  first third). The project holds both creatures.\n"
                     "  --scenes  also write them as BlobTree scenes: DIR/dinosaur.json, DIR/dragon.json\n"
                     "            (sources for `animorph-cli animorph`).\n",
                     makeAnimorphosisDemo);
