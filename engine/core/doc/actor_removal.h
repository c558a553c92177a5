#pragma once
// Deleting an actor as one undoable Command, morph set-up included.
#include <memory>
#include <string>

#include "core/doc/command.h"

namespace animorph {

// Removes the actor with actorId; undo puts it back at the same index.
// When the morph uses the actor as its source or target, the morph set-up is
// removed in the same command (a morph needs both actors); otherwise only the
// actor's own morph entry (stand-in, weight map) goes. Undo brings the actor
// and the whole morph set-up back. Returns null when no such actor exists.
std::unique_ptr<Command> deleteActorCommand(const Project& p, const std::string& actorId);

}  // namespace animorph
