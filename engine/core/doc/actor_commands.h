#pragma once
// Structural edits of a project's actors as undoable Commands (adding,
// deleting, renaming); field edits use setActorField from doc/command.h.
#include <memory>
#include <string>

#include "core/doc/actor_removal.h"  // deleteActorCommand
#include "core/doc/command.h"

namespace animorph {

// Adds actor at the end of the list (its id must be unique: use
// Project::uniqueActorId). Undo removes it again.
std::unique_ptr<Command> addActorCommand(Actor actor);

// Renames an actor (its display name; the id stays). Null when no such actor
// exists or the name is unchanged or empty.
std::unique_ptr<Command> renameActorCommand(const Project& p, const std::string& actorId, const std::string& name);

// An actor for a glTF file: id and name from the file's stem (the name numbered when another
// actor has it: the same file imported twice gives "walker" and "walker 2"), assetPath
// relative to projectDir when that directory is known (else absolute).
Actor actorForAsset(const Project& p, const std::string& absoluteAssetPath, const std::string& projectDir);

}  // namespace animorph
