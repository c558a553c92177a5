// animorph-cli bake-keys P -o C.json: the key-frame animorphosis of a project as a BlobTree scene.
#include <cstdio>

#include "core/animorphosis/bake_keys.h"
#include "core/blobtree/blob_tree_json.h"
#include "app/cli/cli_command.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"

namespace {

using namespace animorph;

int runBakeKeys(const std::vector<std::string>& args) {
  std::string path, output;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-o" || a == "--output") {
      if (i + 1 >= args.size()) return cli::fail("bake-keys", a + " needs a value", 2);
      output = args[++i];
    } else if (!a.empty() && a[0] == '-') {
      return cli::fail("bake-keys", "unknown option " + a, 2);
    } else if (path.empty()) {
      path = a;
    } else {
      return cli::fail("bake-keys", "expected one project", 2);
    }
  }
  if (path.empty() || output.empty()) return cli::fail("bake-keys", "usage: bake-keys PROJECT.animorph -o TREE.json", 2);
  auto p = loadProject(path);
  if (!p) return cli::fail("bake-keys", p.error());
  auto c = projectGenericTree(*p);
  if (!c) return cli::fail("bake-keys", path + ": " + c.error());
  BakedAnimorphosis baked = bakeKeyframes(*c, animorphosisTiming(*p));
  if (auto st = saveBlobTreeScene(baked.tree, output); !st) return cli::fail("bake-keys", st.error());
  const BakeKeysReport& r = baked.report;
  std::printf("wrote %s: %zu nodes, %zu channels, %zu keys, at most %d on one channel (nA + nB + ns = %d)%s\n",
              output.c_str(), c->size(), r.parameters, r.keys, r.mostKeys, r.mostKeysBound,
              r.withinBound ? "" : "; clip loops put more keys than nA + nB + ns on some channels");
  std::printf("largest deviation from the live animorphosis between keys: %g (%s)\n", r.largestDeviation,
              r.largestDeviationAt.empty() ? "none" : r.largestDeviationAt.c_str());
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("bake-keys", "bake a project's animorphosis into a key-frame BlobTree",
                     "usage: animorph-cli bake-keys PROJECT.animorph -o TREE.json\n"
                     "  Bakes the generic tree of the animorphosis into a plain key-framed BlobTree\n"
                     "  scene over its interval: keys at the union of the key times of source, target\n"
                     "  and s, exact at every key. Prints the key counts and the largest deviation\n"
                     "  from the live animorphosis sampled between keys.\n",
                     runBakeKeys);
