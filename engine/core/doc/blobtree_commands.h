#pragma once
// Undoable edits of a BlobTree actor's tree (docs/design.md §5 of the editor: every
// edit is a Command). Each builder applies the edit (blobtree/tree_edit.h) to a
// copy of the actor's tree and returns a command that swaps the whole tree in
// and out; trees are small (a creature is a few kilobytes), and a snapshot
// cannot drift out of step with the tree the way a diff could. A refused edit
// returns the reason ("cannot delete node 4 (sphere): node 2 (difference)
// needs at least 2 children") and builds no command.
#include <memory>
#include <string>
#include <vector>

#include "core/blobtree/tree_edit.h"
#include "core/doc/command.h"
#include "core/util/result.h"

namespace animorph {

// Replaces the tree of actorId with after. Commands with the same non-empty
// mergeKey pushed during one drag fold into one undo step (first before, last after).
std::unique_ptr<Command> setBlobTreeCommand(const Project& p, const std::string& actorId, BlobTree after,
                                            std::string label, std::string mergeKey = {});

// Runs edit on a copy of the actor's tree; the command on success, the edit's
// error (or "no BlobTree actor 'x'") otherwise.
template <class Edit>
Result<std::unique_ptr<Command>> editBlobTree(const Project& p, const std::string& actorId, std::string label,
                                              Edit&& edit, std::string mergeKey = {});

// A new actor of kind blobtree holding makeStarterTree() (a blend of one
// sphere), with an unused id built from name and a name no other actor has
// (Project::uniqueActorName: converting an actor twice gives "X particles" and "X particles 2").
Actor makeBlobTreeActor(const Project& p, const std::string& name);

// Adds a default node of type (blobtree/tree_edit.h makeDefaultNode) under parentId; newId gets its id.
Result<std::unique_ptr<Command>> addBlobNodeCommand(const Project& p, const std::string& actorId, int parentId,
                                                    NodeType type, int* newId = nullptr);
Result<std::unique_ptr<Command>> deleteBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId);
// The copy (fresh ids) goes right after the original; newId gets its id.
Result<std::unique_ptr<Command>> duplicateBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId,
                                                          int* newId = nullptr);
Result<std::unique_ptr<Command>> reparentBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId,
                                                         int newParentId, int index = -1);
Result<std::unique_ptr<Command>> renameBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId,
                                                       const std::string& name);
// setParamValue (see tree_edit.h): key = false edits (keys animated parameters
// at timeSec), key = true is the key button.
Result<std::unique_ptr<Command>> setBlobParamCommand(const Project& p, const std::string& actorId,
                                                     const ParamAddress& a, double timeSec, const ParamSample& value,
                                                     bool key, std::string mergeKey = {});
Result<std::unique_ptr<Command>> deleteBlobKeysCommand(const Project& p, const std::string& actorId,
                                                       const std::vector<KeyRef>& keys);
// Moves keys from their place in `original` (the tree when the drag started)
// by the drag's total offset, so every step of a drag rebuilds from the same
// start and merges into one undo step under mergeKey. moved gets the new refs.
Result<std::unique_ptr<Command>> moveBlobKeysCommand(const Project& p, const std::string& actorId,
                                                     const BlobTree& original,
                                                     const std::vector<KeyChannelRef>& channels, double dtSec,
                                                     float dValue, std::string mergeKey = {},
                                                     std::vector<KeyChannelRef>* moved = nullptr);
Result<std::unique_ptr<Command>> setBlobKeyInterpCommand(const Project& p, const std::string& actorId,
                                                         const std::vector<KeyRef>& keys, KeyInterp interp);
Result<std::unique_ptr<Command>> setBlobKeyTangentModeCommand(const Project& p, const std::string& actorId,
                                                              const std::vector<KeyRef>& keys, bool user);
// Tangent handle drags: like moveBlobKeysCommand, rebuilt from original each step.
Result<std::unique_ptr<Command>> setBlobKeyTangentCommand(const Project& p, const std::string& actorId,
                                                          const BlobTree& original, const KeyChannelRef& k,
                                                          float slopePerSec, std::string mergeKey = {});

// ---- implementation of the template ----
template <class Edit>
Result<std::unique_ptr<Command>> editBlobTree(const Project& p, const std::string& actorId, std::string label,
                                              Edit&& edit, std::string mergeKey) {
  const Actor* a = p.findActor(actorId);
  if (!a || a->kind != ActorKind::BlobTree) return Error{"no BlobTree actor '" + actorId + "'"};
  BlobTree copy = a->blobTree;
  Status s = edit(copy);
  if (!s) return Error{"actor '" + actorId + "': " + s.error()};
  return setBlobTreeCommand(p, actorId, std::move(copy), std::move(label), std::move(mergeKey));
}

}  // namespace animorph
