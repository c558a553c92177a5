#pragma once
// The node hierarchy of a BlobTree actor inside the outliner: click selects,
// double-click renames in place, drag a node onto another to reparent it
// (cycles and child-count limits are refused with a message), right-click
// adds a child of any type, duplicates, renames or deletes.
#include <string>

#include "core/doc/document.h"
#include "ui/common/status_bar.h"

namespace animorph {

struct BlobOutlinerState {
  std::string renamingActor;  // node being renamed: actor and node id
  int renamingNode = -1;
  std::string renameBuffer;
  bool focusRename = false;
};

// Draws the nodes of actorId's tree (call inside the actor's open tree node).
void drawBlobTreeNodes(Document& doc, const std::string& actorId, BlobOutlinerState& st, StatusMessage& status);

// Starts renaming a node in place.
void beginBlobNodeRename(BlobOutlinerState& st, const Document& doc, const std::string& actorId, int nodeId);

}  // namespace animorph
