#pragma once
// Undoable edits of the project's animorphosis (docs/animorphosis.md). Each
// builder checks the edit on a copy of the setup and returns a command that
// swaps the whole setup in and out (a graph is a few kilobytes), or the reason
// it is refused, naming the nodes or actors involved; a refused edit builds no
// command.
#include <memory>
#include <optional>
#include <string>

#include "core/animorphosis/auto_correspond.h"
#include "core/doc/command.h"
#include "core/util/result.h"

namespace animorph {

// Replaces the setup with after. Commands with the same non-empty mergeKey
// pushed during one drag fold into one undo step.
std::unique_ptr<Command> setAnimorphosisCommand(const Project& p, AnimorphosisSetup after, std::string label,
                                                std::string mergeKey = {});

// Starts an animorphosis of two BlobTree actors over [startSec, endSec], its
// graph proposed automatically when autoMap is set (empty otherwise) with autoSettings (their clip
// times are set from the interval; their progress and cancel are used: a cancelled proposal is an
// error saying so).
Result<std::unique_ptr<Command>> createAnimorphosisCommand(const Project& p, const std::string& sourceActorId,
                                                           const std::string& targetActorId, double startSec,
                                                           double endSec, bool autoMap,
                                                           AutoCorrespondSettings autoSettings = {});
// Draws an artist link (refused when it breaks the hierarchy rules; an existing
// automatic link between the same nodes becomes an artist one).
Result<std::unique_ptr<Command>> addCorrespondenceLinkCommand(const Project& p, int nodeA, int nodeB);
Result<std::unique_ptr<Command>> removeCorrespondenceLinkCommand(const Project& p, int nodeA, int nodeB);
// Sets (or, with nullopt, removes) a link's s override.
Result<std::unique_ptr<Command>> setLinkSOverrideCommand(const Project& p, int nodeA, int nodeB,
                                                         std::optional<FloatTrack> s, std::string mergeKey = {});
Result<std::unique_ptr<Command>> setGlobalSCommand(const Project& p, FloatTrack s, std::string mergeKey = {});
Result<std::unique_ptr<Command>> setAnimorphosisIntervalCommand(const Project& p, double startSec, double endSec,
                                                                std::string mergeKey = {});
// Applies the suggestion nodeA -> nodeB (graph.suggestions) as an artist link: refused, naming the
// nodes and the rule, when it breaks a rule of the graph or there is no such suggestion.
Result<std::unique_ptr<Command>> acceptSuggestionCommand(const Project& p, int nodeA, int nodeB);
// Applies every suggestion that keeps the graph valid, most confident first (one undo step); those
// that would break a rule stay suggestions. `accepted` (optional) receives how many were applied.
// Refused when there is no suggestion.
Result<std::unique_ptr<Command>> acceptAllSuggestionsCommand(const Project& p, int* accepted = nullptr);
// Replaces the automatic links by autoCorrespond's, keeping the artist's.
Result<std::unique_ptr<Command>> autoMapCommand(const Project& p, const AutoCorrespondSettings& settings = {},
                                                AutoCorrespondReport* report = nullptr);

}  // namespace animorph
