// animorph-cli correspond P [--json]: the links of a project's animorphosis, or
// the skeleton chain matching of a project's morph (with its artist pairs, which
// --pair / --unpair / --auto / --auto-all edit, saved with -o).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/cli/chain_pair_options.h"
#include "core/standin_morph/chain_matching.h"
#include "core/animorphosis/correspondence_json.h"
#include "core/animorphosis/tree_index.h"
#include "app/cli/cli_command.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"
#include "core/scene/morph_runtime.h"

namespace {

using namespace animorph;

std::string nodeName(const BlobTree& t, int id) {
  const BlobNode* n = t.find(id);
  return n ? nameOfNode(*n) : "missing node " + std::to_string(id);
}

// The skeleton correspondence of a morph between two characters: per chain of each side, its
// features and its partner (or the matched chain it shrinks into / grows from).
// pinned / automatic: the source side's artist flags and automatic matches (null for the target side).
nlohmann::json chainsJson(const SkeletonChains& own, const std::vector<int>& match, const std::vector<float>* cost,
                          const SkeletonCorrespondence* pins = nullptr) {
  nlohmann::json out = nlohmann::json::array();
  for (size_t i = 0; i < own.chains.size(); ++i) {
    const SkeletonChain& c = own.chains[i];
    nlohmann::json j = {{"index", i},          {"name", c.name},         {"nodes", c.nodes},
                        {"segments", c.segments}, {"parent", c.parent},    {"side", c.side},
                        {"direction", {c.direction.x, c.direction.y, c.direction.z}},
                        {"length", c.length},   {"subtree", c.subtree},   {"match", match[i]}};
    if (cost && match[i] >= 0) j["cost"] = (*cost)[i];
    if (match[i] < 0) j["anchor_chain"] = matchedAnchor(own, match, int(i));  // the nearest matched ancestor (-1: none)
    if (pins) j["artist"] = bool(pins->pinned[i]), j["automatic"] = pins->automatic[i];
    out.push_back(std::move(j));
  }
  return out;
}

// pins: the source side's artist pairs, marked "[artist]" with what the automatic rule would pick.
void printChains(const char* side, const char* verb, const SkeletonChains& own, const SkeletonChains& other,
                 const std::vector<int>& match, const std::vector<float>* cost,
                 const SkeletonCorrespondence* pins = nullptr) {
  std::printf("%s chains:\n", side);
  for (size_t i = 0; i < own.chains.size(); ++i) {
    const SkeletonChain& c = own.chains[i];
    std::printf("  %2zu %-20s %2zu nodes %2zu segments  side %+d  dir (%5.2f %5.2f %5.2f)  length %.2f  subtree %.2f  ",
                i, c.name.c_str(), c.nodes.size(), c.segments.size(), c.side, double(c.direction.x),
                double(c.direction.y), double(c.direction.z), double(c.length), double(c.subtree));
    if (match[i] >= 0) {
      std::printf("<-> %d %s", match[i], other.chains[size_t(match[i])].name.c_str());
      if (cost) std::printf("  cost %.2f", double((*cost)[i]));
    } else if (const int anchor = matchedAnchor(own, match, int(i)); anchor < 0) {
      std::printf("unmatched: %s the other side's root", verb);
    } else {
      std::printf("unmatched: %s %d %s (the partner of %d %s)", verb, match[size_t(anchor)],
                  other.chains[size_t(match[size_t(anchor)])].name.c_str(), anchor, own.chains[size_t(anchor)].name.c_str());
    }
    if (pins && pins->pinned[i]) {
      const int a = pins->automatic[i];
      std::printf("  [artist; automatic: %s]", a >= 0 ? other.chains[size_t(a)].name.c_str() : "unmatched");
    }
    std::printf("\n");
  }
}

// edits: the chain pair options, applied to p's pairs; output: where p is saved with them (empty: not saved).
int correspondMorph(Project p, const std::string& path, bool asJson, const std::vector<cli::ChainPairEdit>& edits,
                    const std::string& output) {
  namespace fs = std::filesystem;
  AssetCache assets;
  auto rt = prepareMorph(p, fs::absolute(fs::path(path)).parent_path().string(), assets);
  if (!rt) return cli::fail("correspond", path + ": " + rt.error());
  auto c = morphSkeletonCorrespondence((*rt)->source, (*rt)->target, p.morph.chainPairs);
  if (!c) return cli::fail("correspond", path + ": skeleton correspondence: " + c.error());
  if (!edits.empty()) {
    std::string error;
    if (!cli::applyChainPairEdits(edits, *c, p.morph.chainPairs, error)) return cli::fail("correspond", path + ": " + error, 2);
    c = morphSkeletonCorrespondence((*rt)->source, (*rt)->target, p.morph.chainPairs);
    if (!c) return cli::fail("correspond", path + ": skeleton correspondence: " + c.error());
  }
  if (!output.empty()) {
    if (auto st = saveProject(p, output); !st) return cli::fail("correspond", st.error());
  }
  for (const std::string& w : c->warnings) std::fprintf(stderr, "animorph-cli correspond: %s: morph.%s\n", path.c_str(), w.c_str());
  const MorphSetup& m = p.morph;
  size_t matched = 0, artist = 0;
  for (int k : c->sourceMatch) matched += k >= 0;
  for (char k : c->pinned) artist += k != 0;
  if (asJson) {
    nlohmann::json j = {{"source", m.sourceActorId},
                        {"target", m.targetActorId},
                        {"method", morphMethodName(m.method)},
                        {"matched", matched},
                        {"artist_pairs", artist},
                        {"warnings", c->warnings},
                        {"source_chains", chainsJson(c->source, c->sourceMatch, &c->cost, &*c)},
                        {"target_chains", chainsJson(c->target, c->targetMatch, nullptr)}};
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::printf("%s -> %s: skeleton correspondence, %zu source chains, %zu target chains, %zu matched, %zu set by the artist (method %s%s)\n",
              m.sourceActorId.c_str(), m.targetActorId.c_str(), c->source.chains.size(), c->target.chains.size(), matched,
              artist, morphMethodName(m.method),
              m.method == MorphMethod::SkeletonCorrespondence ? "" : ": the morph does not use it");
  printChains("source", "shrinks into", c->source, c->target, c->sourceMatch, &c->cost, &*c);
  printChains("target", "grows from", c->target, c->source, c->targetMatch, nullptr);
  return 0;
}

int runCorrespond(const std::vector<std::string>& args) {
  std::string path, output;
  bool asJson = false;
  std::vector<cli::ChainPairEdit> edits;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::string error;
    if (a == "--json") asJson = true;
    else if (a == "-o") {
      if (i + 1 >= args.size()) return cli::fail("correspond", "-o: expected an output project path", 2);
      output = args[++i];
    } else if (cli::readChainPairOption(args, i, edits, error)) {
      if (!error.empty()) return cli::fail("correspond", error, 2);
    } else if (!a.empty() && a[0] == '-') return cli::fail("correspond", "unknown option " + a, 2);
    else if (path.empty()) path = a;
    else return cli::fail("correspond", "expected one project", 2);
  }
  if (path.empty()) return cli::fail("correspond", "usage: correspond PROJECT.animorph [--json] [--pair S=T] [--unpair S] [--auto S] [--auto-all] [-o OUT]", 2);
  auto p = loadProject(path);
  if (!p) return cli::fail("correspond", p.error());
  if (p->morph.enabled()) return correspondMorph(std::move(*p), path, asJson, edits, output);
  if (!edits.empty() || !output.empty())
    return cli::fail("correspond", path + ": --pair, --unpair, --auto and -o edit a morph's chain pairs; the project has no morph", 2);
  if (Status s = checkAnimorphosis(*p); !s) return cli::fail("correspond", path + ": " + s.error());
  const AnimorphosisSetup& m = p->animorphosis;
  const BlobTree& a = p->findActor(m.sourceActorId)->blobTree;
  const BlobTree& b = p->findActor(m.targetActorId)->blobTree;
  auto c = projectGenericTree(*p);
  if (asJson) {
    nlohmann::json j = correspondenceToJson(m.graph);
    for (const char* list : {"links", "suggestions"}) {
      if (!j.contains(list)) continue;
      for (auto& l : j[list]) {
        l["a_name"] = nodeName(a, l["a"].get<int>());
        l["b_name"] = nodeName(b, l["b"].get<int>());
      }
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
  if (!m.graph.suggestions.empty())
    std::printf("%zu suggestions (below the confidence threshold, not applied; accept them in the correspondence "
                "editor):\n",
                m.graph.suggestions.size());
  for (const auto& l : m.graph.suggestions)
    std::printf("  %-32s -> %-32s confidence %.2f  suggestion\n", nodeName(a, l.nodeA).c_str(),
                nodeName(b, l.nodeB).c_str(), double(l.confidence));
  if (!c) return cli::fail("correspond", path + ": " + c.error());
  std::printf("generic tree: %zu nodes, %d split copies, %d null partners\n", c->size(), c->splitCopies,
              c->nullPartners);
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("correspond", "print the correspondence of a project's animorphosis or morph",
                     "usage: animorph-cli correspond PROJECT.animorph [--json] [--pair SRC=TGT] [--unpair SRC]\n"
                     "                                [--auto SRC] [--auto-all] [-o OUT.animorph]\n"
                     "  An animorphosis: prints each link (source node -> target node, confidence,\n"
                     "  artist or automatic, s override) and the size of the generic tree; --json\n"
                     "  prints the graph as JSON with node names added.\n"
                     "  A morph between two characters: prints the skeleton correspondence (the\n"
                     "  skeleton_correspondence method's): each side's chains (split at branch\n"
                     "  joints) with side, direction from the root, share of length and of segments,\n"
                     "  and the chain each matches (with its cost), or the matched chain an\n"
                     "  unmatched one shrinks into / grows from. Chains the artist paired are marked\n"
                     "  [artist] with what the automatic rule would pick. Chains are named by their\n"
                     "  first joint: --pair SRC=TGT pairs source chain SRC with target chain TGT,\n"
                     "  --unpair SRC leaves SRC unmatched, --auto SRC gives SRC back to the automatic\n"
                     "  matching, --auto-all all chains; -o saves the project with the edited pairs\n"
                     "  (keep it in the same folder: asset paths are relative to it).\n",
                     runCorrespond);
