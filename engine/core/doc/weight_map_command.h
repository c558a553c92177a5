#pragma once
// Undoable change of one morph actor's weight map (a paint stroke, a fill, an
// import): stores the whole map before and after, so undo restores it exactly
// (an actor that had no map gets none back).
#include <memory>
#include <string>
#include <vector>

#include "core/doc/command.h"
#include "core/util/result.h"

namespace animorph {

// Sets actorId's weight map to after (one entry per vertex over the
// character's meshNodes(), each in [0, 1]; empty: no map). Errors: the actor
// is not in the project's morph, a value outside [0, 1]. A source or target
// actor with no entry in morph.actors gets one (undo removes it again).
Result<std::unique_ptr<Command>> setWeightMapCommand(const Project& p, const std::string& actorId,
                                                     std::vector<float> after, std::string label);

}  // namespace animorph
