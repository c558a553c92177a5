// animorph-cli make-blob-demo DIR: writes the demo BlobTree creature scene.
#include <filesystem>
#include <iostream>

#include "blobtree/blob_tree_json.h"
#include "blobtree/validate.h"
#include "cli/cli_command.h"
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
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("make-blob-demo", "write the demo animated BlobTree creature (blob_creature.json)",
                     "usage: animorph-cli make-blob-demo DIR\n"
                     "  Writes DIR/blob_creature.json: a BlobTree creature with a frame hierarchy for\n"
                     "  body, legs and head, a swaying spline-of-nodes tail and a breathing torso.\n",
                     makeBlobDemo);
