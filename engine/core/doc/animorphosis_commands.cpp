#include "core/doc/animorphosis_commands.h"

#include <algorithm>

#include "core/animorphosis/tree_index.h"
#include "core/animorphosis/validate_correspondence.h"
#include "core/project/animorphosis_project.h"

namespace animorph {

namespace {

AnimorphosisSetup* setupOf(Project& p) { return &p.animorphosis; }

// Checks `after` in a copy of the project; the command, or the reason.
Result<std::unique_ptr<Command>> checked(const Project& p, AnimorphosisSetup after, std::string label,
                                         std::string mergeKey = {}) {
  Project trial = p;
  trial.animorphosis = after;
  if (Status s = checkAnimorphosis(trial); !s) return Error{s.error()};
  return setAnimorphosisCommand(p, std::move(after), std::move(label), std::move(mergeKey));
}

std::string linkLabel(const Project& p, int nodeA, int nodeB) {
  auto name = [&](const std::string& actor, int id) {
    const Actor* a = p.findActor(actor);
    const BlobNode* n = a ? a->blobTree.find(id) : nullptr;
    return n ? nameOfNode(*n) : "node " + std::to_string(id);
  };
  return name(p.animorphosis.sourceActorId, nodeA) + " -> " + name(p.animorphosis.targetActorId, nodeB);
}

}  // namespace

std::unique_ptr<Command> setAnimorphosisCommand(const Project& p, AnimorphosisSetup after, std::string label,
                                                std::string mergeKey) {
  return std::make_unique<SetValueCommand<AnimorphosisSetup>>(std::move(label), setupOf, p.animorphosis,
                                                              std::move(after), std::move(mergeKey));
}

Result<std::unique_ptr<Command>> createAnimorphosisCommand(const Project& p, const std::string& sourceActorId,
                                                           const std::string& targetActorId, double startSec,
                                                           double endSec, bool autoMap,
                                                           AutoCorrespondSettings st) {
  AnimorphosisSetup a;
  a.sourceActorId = sourceActorId;
  a.targetActorId = targetActorId;
  a.startSec = startSec;
  a.endSec = endSec;
  Project trial = p;
  trial.animorphosis = a;
  if (Status s = checkAnimorphosis(trial); !s) return Error{s.error()};
  if (autoMap) {
    AnimorphosisTiming t = animorphosisTiming(trial);
    st.timeSecA = t.source.localTime(startSec);
    st.timeSecB = t.target.localTime(startSec);
    auto g = autoCorrespond(p.findActor(sourceActorId)->blobTree, p.findActor(targetActorId)->blobTree, {}, st);
    if (!g) return Error{"animorphosis: " + g.error()};
    a.graph = std::move(*g);
  }
  return checked(p, std::move(a), "Create animorphosis " + sourceActorId + " -> " + targetActorId);
}

Result<std::unique_ptr<Command>> addCorrespondenceLinkCommand(const Project& p, int nodeA, int nodeB) {
  AnimorphosisSetup a = p.animorphosis;
  int i = a.graph.find(nodeA, nodeB);
  if (i >= 0) {
    if (a.graph.links[size_t(i)].artist) return Error{"animorphosis: link " + linkLabel(p, nodeA, nodeB) + " exists"};
    a.graph.links[size_t(i)].artist = true;
    a.graph.links[size_t(i)].confidence = 1.0f;
  } else {
    a.graph.links.push_back({nodeA, nodeB, {}, 1.0f, true});
  }
  // Drawing a suggested link by hand accepts the suggestion.
  if (int k = a.graph.findSuggestion(nodeA, nodeB); k >= 0) a.graph.suggestions.erase(a.graph.suggestions.begin() + k);
  return checked(p, std::move(a), "Link " + linkLabel(p, nodeA, nodeB));
}

Result<std::unique_ptr<Command>> removeCorrespondenceLinkCommand(const Project& p, int nodeA, int nodeB) {
  AnimorphosisSetup a = p.animorphosis;
  int i = a.graph.find(nodeA, nodeB);
  if (i < 0) return Error{"animorphosis: there is no link " + linkLabel(p, nodeA, nodeB)};
  a.graph.links.erase(a.graph.links.begin() + i);
  return checked(p, std::move(a), "Cut link " + linkLabel(p, nodeA, nodeB));
}

Result<std::unique_ptr<Command>> setLinkSOverrideCommand(const Project& p, int nodeA, int nodeB,
                                                         std::optional<FloatTrack> s, std::string mergeKey) {
  AnimorphosisSetup a = p.animorphosis;
  int i = a.graph.find(nodeA, nodeB);
  if (i < 0) return Error{"animorphosis: there is no link " + linkLabel(p, nodeA, nodeB)};
  a.graph.links[size_t(i)].sOverride = std::move(s);
  return checked(p, std::move(a), "s(t) of link " + linkLabel(p, nodeA, nodeB), std::move(mergeKey));
}

Result<std::unique_ptr<Command>> setGlobalSCommand(const Project& p, FloatTrack s, std::string mergeKey) {
  AnimorphosisSetup a = p.animorphosis;
  a.globalS = std::move(s);
  return checked(p, std::move(a), "Animorphosis s(t)", std::move(mergeKey));
}

Result<std::unique_ptr<Command>> setAnimorphosisIntervalCommand(const Project& p, double startSec, double endSec,
                                                                std::string mergeKey) {
  AnimorphosisSetup a = p.animorphosis;
  a.startSec = startSec;
  a.endSec = endSec;
  return checked(p, std::move(a), "Animorphosis interval", std::move(mergeKey));
}

Result<std::unique_ptr<Command>> acceptSuggestionCommand(const Project& p, int nodeA, int nodeB) {
  AnimorphosisSetup a = p.animorphosis;
  int i = a.graph.findSuggestion(nodeA, nodeB);
  if (i < 0) return Error{"animorphosis: there is no suggestion " + linkLabel(p, nodeA, nodeB)};
  a.graph.suggestions.erase(a.graph.suggestions.begin() + i);
  if (a.graph.find(nodeA, nodeB) < 0) a.graph.links.push_back({nodeA, nodeB, {}, 1.0f, true});
  return checked(p, std::move(a), "Accept suggestion " + linkLabel(p, nodeA, nodeB));
}

Result<std::unique_ptr<Command>> acceptAllSuggestionsCommand(const Project& p, int* accepted) {
  if (Status s = checkAnimorphosis(p); !s) return Error{s.error()};
  AnimorphosisSetup a = p.animorphosis;
  if (a.graph.suggestions.empty()) return Error{"animorphosis: there are no suggestions to accept"};
  std::vector<CorrespondenceLink> pending = a.graph.suggestions;
  std::stable_sort(pending.begin(), pending.end(),
                   [](const auto& x, const auto& y) { return x.confidence > y.confidence; });
  a.graph.suggestions.clear();
  const BlobTree& ta = p.findActor(a.sourceActorId)->blobTree;
  const BlobTree& tb = p.findActor(a.targetActorId)->blobTree;
  int done = 0;
  for (const CorrespondenceLink& l : pending) {
    if (a.graph.find(l.nodeA, l.nodeB) >= 0) continue;
    a.graph.links.push_back({l.nodeA, l.nodeB, {}, 1.0f, true});
    if (validateCorrespondence(ta, tb, a.graph).ok()) {
      ++done;
    } else {
      a.graph.links.pop_back();
      a.graph.suggestions.push_back(l);
    }
  }
  if (accepted) *accepted = done;
  if (done == 0) return Error{"animorphosis: none of the " + std::to_string(pending.size()) +
                              " suggestions can be accepted without breaking a rule of the graph"};
  return checked(p, std::move(a), "Accept " + std::to_string(done) + " suggestion" + (done == 1 ? "" : "s"));
}

Result<std::unique_ptr<Command>> autoMapCommand(const Project& p, const AutoCorrespondSettings& settings,
                                                AutoCorrespondReport* report) {
  if (Status s = checkAnimorphosis(p); !s) return Error{s.error()};
  const AnimorphosisSetup& m = p.animorphosis;
  auto g = autoCorrespond(p.findActor(m.sourceActorId)->blobTree, p.findActor(m.targetActorId)->blobTree, m.graph,
                          settings, report);
  if (!g) return Error{"animorphosis: " + g.error()};
  AnimorphosisSetup a = m;
  a.graph = std::move(*g);
  return checked(p, std::move(a), "Auto-map correspondence");
}

}  // namespace animorph
