// animorph-cli animorph SOURCE TARGET -o P.animorph: a project holding an animorphosis of two BlobTrees.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>

#include "core/animorphosis/tree_index.h"
#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/tree_edit.h"
#include "app/cli/cli_command.h"
#include "core/doc/animorphosis_commands.h"
#include "core/doc/blobtree_commands.h"
#include "core/project/project_io.h"

namespace {

using namespace animorph;

bool parseFrame(const std::string& v, double& out) {
  char* end = nullptr;
  out = std::strtod(v.c_str(), &end);
  return end && *end == '\0' && std::isfinite(out);
}

// A BlobTree scene file, or a project holding exactly one BlobTree actor.
Result<BlobTree> loadTree(const std::string& path) {
  if (path.size() < 9 || path.compare(path.size() - 9, 9, ".animorph") != 0) return loadBlobTreeScene(path);
  auto p = loadProject(path);
  if (!p) return Error{p.error()};
  const Actor* found = nullptr;
  int count = 0;
  for (const Actor& a : p->actors)
    if (a.kind == ActorKind::BlobTree) found = &a, ++count;
  if (count != 1)
    return Error{path + ": holds " + std::to_string(count) + " BlobTree actors; expected exactly one"};
  return found->blobTree;
}

int runAnimorph(const std::vector<std::string>& args) {
  std::vector<std::string> inputs;
  std::string output;
  bool autoMap = false;
  double startFrame = 24.0, endFrame = 72.0;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-o" || a == "--output" || a == "--start" || a == "--end") {
      if (i + 1 >= args.size()) return cli::fail("animorph", a + " needs a value", 2);
      const std::string& v = args[++i];
      if (a == "--start" || a == "--end") {
        if (!parseFrame(v, a == "--start" ? startFrame : endFrame))
          return cli::fail("animorph", a + ": expected a frame number, got '" + v + "'", 2);
      } else {
        output = v;
      }
    } else if (a == "--auto") {
      autoMap = true;
    } else if (!a.empty() && a[0] == '-') {
      return cli::fail("animorph", "unknown option " + a, 2);
    } else {
      inputs.push_back(a);
    }
  }
  if (inputs.size() != 2 || output.empty())
    return cli::fail("animorph", "usage: animorph SOURCE TARGET -o PROJECT.animorph [--auto] [--start F --end F]", 2);
  if (!(endFrame > startFrame)) return cli::fail("animorph", "--end must come after --start", 2);

  Project p;
  p.name = "animorphosis";
  const char* names[2] = {"source", "target"};
  std::string ids[2];
  double lastKey = 0.0;
  for (int k = 0; k < 2; ++k) {
    auto tree = loadTree(inputs[size_t(k)]);
    if (!tree) return cli::fail("animorph", tree.error());
    Actor a = makeBlobTreeActor(p, names[k]);
    a.blobTree = std::move(*tree);
    lastKey = std::max(lastKey, animationEndSec(a.blobTree));
    ids[k] = a.id;
    p.actors.push_back(std::move(a));
  }
  p.timeline.frameStart = 0;
  p.timeline.frameEnd = int(std::ceil(std::max(endFrame + startFrame, p.timeline.secToFrame(lastKey))));
  auto cmd = createAnimorphosisCommand(p, ids[0], ids[1], p.timeline.frameToSec(startFrame),
                                       p.timeline.frameToSec(endFrame), autoMap);
  if (!cmd) return cli::fail("animorph", cmd.error());
  (*cmd)->apply(p);
  if (auto st = saveProject(p, output); !st) return cli::fail("animorph", st.error());
  const CorrespondenceGraph& g = p.animorphosis.graph;
  std::printf("wrote %s: %s -> %s over frames %g..%g at %g fps, %zu links%s", output.c_str(), inputs[0].c_str(),
              inputs[1].c_str(), startFrame, endFrame, p.timeline.fps, g.links.size(), autoMap ? " (automatic)" : "");
  if (autoMap) std::printf(", %zu suggestions (not applied)", g.suggestions.size());
  std::printf("\n");
  const BlobTree& ta = p.actors[0].blobTree;
  const BlobTree& tb = p.actors[1].blobTree;
  auto name = [](const BlobTree& t, int id) {
    const BlobNode* n = t.find(id);
    return n ? nameOfNode(*n) : "node " + std::to_string(id);
  };
  for (const CorrespondenceLink& l : g.suggestions)
    std::printf("  suggestion: %s -> %s, confidence %.2f\n", name(ta, l.nodeA).c_str(), name(tb, l.nodeB).c_str(),
                double(l.confidence));
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("animorph", "make a project morphing one animated BlobTree into another (animorphosis)",
                     "usage: animorph-cli animorph SOURCE TARGET -o PROJECT.animorph [--auto] [--start F --end F]\n"
                     "  SOURCE, TARGET: BlobTree scene files (or projects holding a BlobTree).\n"
                     "  Writes a project with both as BlobTree actors and an animorphosis from SOURCE to\n"
                     "  TARGET over frames F..F (default 24..72, at 24 fps), both animations playing.\n"
                     "  --auto  propose the correspondence graph automatically (else it starts empty:\n"
                     "          every part shrinks or grows).\n",
                     runAnimorph);
