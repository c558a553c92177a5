// animorph-cli correspond P [--json]: the links of a project's animorphosis, or
// the skeleton chain matching of a project's morph.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "morph/chain_matching.h"
#include "animorph/correspondence_json.h"
#include "animorph/tree_index.h"
#include "cli/cli_command.h"
#include "doc/animorphosis_project.h"
#include "doc/project_io.h"
#include "morph/morph_runtime.h"

namespace {

using namespace animorph;

std::string nodeName(const BlobTree& t, int id) {
  const BlobNode* n = t.find(id);
  return n ? nameOfNode(*n) : "missing node " + std::to_string(id);
}

// The skeleton correspondence of a morph between two characters: per chain of each side, its
// features and its partner (or the matched chain it shrinks into / grows from).
nlohmann::json chainsJson(const SkeletonChains& own, const std::vector<int>& match, const std::vector<float>* cost) {
  nlohmann::json out = nlohmann::json::array();
  for (size_t i = 0; i < own.chains.size(); ++i) {
    const SkeletonChain& c = own.chains[i];
    nlohmann::json j = {{"index", i},          {"name", c.name},         {"nodes", c.nodes},
                        {"segments", c.segments}, {"parent", c.parent},    {"side", c.side},
                        {"direction", {c.direction.x, c.direction.y, c.direction.z}},
                        {"length", c.length},   {"subtree", c.subtree},   {"match", match[i]}};
    if (cost && match[i] >= 0) j["cost"] = (*cost)[i];
    if (match[i] < 0) j["anchor_chain"] = matchedAnchor(own, match, int(i));  // the nearest matched ancestor (-1: none)
    out.push_back(std::move(j));
  }
  return out;
}

void printChains(const char* side, const char* verb, const SkeletonChains& own, const SkeletonChains& other,
                 const std::vector<int>& match, const std::vector<float>* cost) {
  std::printf("%s chains:\n", side);
  for (size_t i = 0; i < own.chains.size(); ++i) {
    const SkeletonChain& c = own.chains[i];
    std::printf("  %2zu %-20s %2zu nodes %2zu segments  side %+d  dir (%5.2f %5.2f %5.2f)  length %.2f  subtree %.2f  ",
                i, c.name.c_str(), c.nodes.size(), c.segments.size(), c.side, double(c.direction.x),
                double(c.direction.y), double(c.direction.z), double(c.length), double(c.subtree));
    if (match[i] >= 0) {
      std::printf("<-> %d %s", match[i], other.chains[size_t(match[i])].name.c_str());
      if (cost) std::printf("  cost %.2f", double((*cost)[i]));
      std::printf("\n");
      continue;
    }
    const int anchor = matchedAnchor(own, match, int(i));
    if (anchor < 0) std::printf("unmatched: %s the other side's root\n", verb);
    else
      std::printf("unmatched: %s %d %s (the partner of %d %s)\n", verb, match[size_t(anchor)],
                  other.chains[size_t(match[size_t(anchor)])].name.c_str(), anchor, own.chains[size_t(anchor)].name.c_str());
  }
}

int correspondMorph(const Project& p, const std::string& path, bool asJson) {
  namespace fs = std::filesystem;
  AssetCache assets;
  auto rt = prepareMorph(p, fs::absolute(fs::path(path)).parent_path().string(), assets);
  if (!rt) return cli::fail("correspond", path + ": " + rt.error());
  auto c = morphSkeletonCorrespondence((*rt)->source, (*rt)->target);
  if (!c) return cli::fail("correspond", path + ": skeleton correspondence: " + c.error());
  const MorphSetup& m = (*rt)->setup;
  size_t matched = 0;
  for (int k : c->sourceMatch) matched += k >= 0;
  if (asJson) {
    nlohmann::json j = {{"source", m.sourceActorId},
                        {"target", m.targetActorId},
                        {"method", morphMethodName(m.method)},
                        {"matched", matched},
                        {"source_chains", chainsJson(c->source, c->sourceMatch, &c->cost)},
                        {"target_chains", chainsJson(c->target, c->targetMatch, nullptr)}};
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::printf("%s -> %s: skeleton correspondence, %zu source chains, %zu target chains, %zu matched (method %s%s)\n",
              m.sourceActorId.c_str(), m.targetActorId.c_str(), c->source.chains.size(), c->target.chains.size(), matched,
              morphMethodName(m.method),
              m.method == MorphMethod::SkeletonCorrespondence ? "" : ": the morph does not use it");
  printChains("source", "shrinks into", c->source, c->target, c->sourceMatch, &c->cost);
  printChains("target", "grows from", c->target, c->source, c->targetMatch, nullptr);
  return 0;
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
  if (p->morph.enabled()) return correspondMorph(*p, path, asJson);
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

ANIMORPH_CLI_COMMAND("correspond", "print the correspondence of a project's animorphosis or morph",
                     "usage: animorph-cli correspond PROJECT.animorph [--json]\n"
                     "  An animorphosis: prints each link (source node -> target node, confidence,\n"
                     "  artist or automatic, s override) and the size of the generic tree; --json\n"
                     "  prints the graph as JSON with node names added.\n"
                     "  A morph between two characters: prints the skeleton correspondence (the\n"
                     "  skeleton_correspondence method's): each side's chains (split at branch\n"
                     "  joints) with side, direction from the root, share of length and of segments,\n"
                     "  and the chain each matches (with its cost), or the matched chain an\n"
                     "  unmatched one shrinks into / grows from.\n",
                     runCorrespond);
