// animorph-cli correspond P [--json]: the links of a project's animorphosis.
#include <cstdio>
#include <iostream>

#include "animorph/correspondence_json.h"
#include "animorph/tree_index.h"
#include "cli/cli_command.h"
#include "doc/animorphosis_project.h"
#include "doc/project_io.h"

namespace {

using namespace animorph;

std::string nodeName(const BlobTree& t, int id) {
  const BlobNode* n = t.find(id);
  return n ? nameOfNode(*n) : "missing node " + std::to_string(id);
}

int runCorrespond(const std::vector<std::string>& args) {
  std::string path;
  bool asJson = false;
  for (const auto& a : args) {
    if (a == "--json") asJson = true;
    else if (!a.empty() && a[0] == '-') return cli::fail("correspond", "unknown option " + a, 2);
    else if (path.empty()) path = a;
    else return cli::fail("correspond", "expected one project", 2);
  }
  if (path.empty()) return cli::fail("correspond", "usage: correspond PROJECT.animorph [--json]", 2);
  auto p = loadProject(path);
  if (!p) return cli::fail("correspond", p.error());
  if (Status s = checkAnimorphosis(*p); !s) return cli::fail("correspond", path + ": " + s.error());
  const AnimorphosisSetup& m = p->animorphosis;
  const BlobTree& a = p->findActor(m.sourceActorId)->blobTree;
  const BlobTree& b = p->findActor(m.targetActorId)->blobTree;
  auto c = projectGenericTree(*p);
  if (asJson) {
    nlohmann::json j = correspondenceToJson(m.graph);
    for (auto& l : j["links"]) {
      l["a_name"] = nodeName(a, l["a"].get<int>());
      l["b_name"] = nodeName(b, l["b"].get<int>());
    }
    j["source"] = m.sourceActorId;
    j["target"] = m.targetActorId;
    j["start"] = m.startSec;
    j["end"] = m.endSec;
    j["generic_tree"] = c ? nlohmann::json{{"nodes", c->size()}, {"split_copies", c->splitCopies},
                                           {"null_partners", c->nullPartners}}
                          : nlohmann::json{{"error", c.error()}};
    std::cout << j.dump(2) << "\n";
    return c ? 0 : 1;
  }
  std::printf("%s -> %s over %g..%g s, %zu links\n", m.sourceActorId.c_str(), m.targetActorId.c_str(), m.startSec,
              m.endSec, m.graph.links.size());
  for (const auto& l : m.graph.links)
    std::printf("  %-32s -> %-32s confidence %.2f  %s%s\n", nodeName(a, l.nodeA).c_str(), nodeName(b, l.nodeB).c_str(),
                double(l.confidence), l.artist ? "artist" : "automatic", l.sOverride ? "  s override" : "");
  if (!c) return cli::fail("correspond", path + ": " + c.error());
  std::printf("generic tree: %zu nodes, %d split copies, %d null partners\n", c->size(), c->splitCopies,
              c->nullPartners);
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("correspond", "print the correspondence graph of a project's animorphosis",
                     "usage: animorph-cli correspond PROJECT.animorph [--json]\n"
                     "  Prints each link (source node -> target node, confidence, artist or automatic,\n"
                     "  s override) and the size of the generic tree; --json prints the graph as JSON\n"
                     "  with node names added.\n",
                     runCorrespond);
