#pragma once
// Undoable edits of a morph actor's stand-in (issue 4, stand-in editing):
// moving and re-radiusing a segment, adding, deleting, rebinding, refitting.
// Each command swaps the actor's stand-in together with its segment tracks
// (MorphSetup::actors[i].segmentTracks, which index segments by position), so
// an edit that adds or removes a segment keeps the keyed tracks on the
// segments they belong to and undo restores both exactly. Refused edits
// return the reason and build no command.
#include <memory>
#include <string>
#include <vector>

#include "core/doc/command.h"
#include "core/util/result.h"

namespace animorph {

// Pure edits of an actor's morph data (the commands run these on copies).
// Inserts seg before index at (clamped to [0, size]); tracks of later segments are renumbered.
void insertStandinSegment(ActorMorph& am, int at, const StandinSegment& seg);
// Erases segment index: its tracks are dropped, later ones renumbered. False when out of range.
bool eraseStandinSegment(ActorMorph& am, int index);
// Replaces the whole stand-in (a refit). Each old segment's tracks move to the
// new segment on the same node (the k-th old one on a node to the k-th new
// one); tracks of segments with no counterpart are dropped. Returns how many.
size_t replaceStandin(ActorMorph& am, Standin after);

// Sets segment index of actorId's stand-in to after. Commands with the same
// non-empty mergeKey during one drag fold into one undo step.
Result<std::unique_ptr<Command>> setStandinSegmentCommand(const Project& p, const std::string& actorId, int index,
                                                          const StandinSegment& after, std::string label,
                                                          std::string mergeKey = {});
// Inserts seg before index at (at = size appends).
Result<std::unique_ptr<Command>> insertStandinSegmentCommand(const Project& p, const std::string& actorId, int at,
                                                             const StandinSegment& seg, std::string label);
Result<std::unique_ptr<Command>> deleteStandinSegmentCommand(const Project& p, const std::string& actorId, int index);
// Replaces the stand-in (see replaceStandin for the tracks).
Result<std::unique_ptr<Command>> replaceStandinCommand(const Project& p, const std::string& actorId, Standin after,
                                                       std::string label);

}  // namespace animorph
