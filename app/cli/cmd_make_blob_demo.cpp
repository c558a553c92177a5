// animorph-cli make-blob-demo DIR: writes the demo BlobTree creature scene.
#include <filesystem>
#include <iostream>

#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/validate.h"
#include "app/cli/cli_command.h"
#include "core/doc/blobtree_commands.h"
#include "core/project/project_io.h"
#include "demo/blob_creature.h"

namespace {

int makeBlobDemo(const std::vector<std::string>& args) {
  if (args.size() != 1 || (!args[0].empty() && args[0][0] == '-'))
    return animorph::cli::fail("make-blob-demo", "expected one argument: the output directory", 2);
  std::filesystem::path dir(args[0]);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return animorph::cli::fail("make-blob-demo", dir.string() + ": cannot create directory: " + ec.message());
  animorph::BlobTree tree = animorph::makeBlobCreature();
  if (auto s = animorph::validateBlobTree(tree); !s) return animorph::cli::fail("make-blob-demo", "internal: " + s.error(), 3);
  std::string path = (dir / "blob_creature.json").string();
  if (auto s = animorph::saveBlobTreeScene(tree, path); !s) return animorph::cli::fail("make-blob-demo", s.error());
  std::cout << "wrote " << path << " (" << tree.root.subtreeSize() << " nodes, loops over "
            << animorph::kBlobCreatureLoopSec << " s)\n";

  // The same creature as the BlobTree actor of a project, one loop on the timeline.
  animorph::Project project;
  project.name = "BlobTree creature";
  project.timeline.fps = 24.0;
  project.timeline.frameStart = 0;
  project.timeline.frameEnd = int(animorph::kBlobCreatureLoopSec * project.timeline.fps);
  project.view.showSkeleton = false;
  animorph::Actor actor = animorph::makeBlobTreeActor(project, "Creature");
  actor.blobTree = tree;
  project.actors.push_back(actor);
  std::string projectPath = (dir / "blob_demo.animorph").string();
  if (auto s = animorph::saveProject(project, projectPath); !s) return animorph::cli::fail("make-blob-demo", s.error());
  std::cout << "wrote " << projectPath << " (actor '" << actor.id << "', frames 0.." << project.timeline.frameEnd
            << ")\n";
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("make-blob-demo", "write the demo animated BlobTree creature (scene and project)",
                     "usage: animorph-cli make-blob-demo DIR\n"
                     "  Writes DIR/blob_creature.json: a BlobTree creature with a frame hierarchy for\n"
                     "  body, legs and head, a swaying spline-of-nodes tail and a breathing torso, and\n"
                     "  DIR/blob_demo.animorph: a project with the creature as its BlobTree actor.\n",
                     makeBlobDemo);
