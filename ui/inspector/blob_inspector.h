#pragma once
// Inspector for a selected BlobTree node: name, type, and every parameter
// (floats, vectors, rotations as Euler degrees, control-point lists) showing
// its value at the current frame, with a key button per parameter.
//
// Keying (documented in docs/editor.md): the key button keys the shown value
// at the current frame. Editing a field of an animated parameter (two or more
// keys) sets the key at the current frame, creating it if needed; editing a
// parameter without animation changes it for all times. There is no auto-key
// of constant parameters: animation starts with the key button.
#include <string>

#include <glm/glm.hpp>

#include "core/doc/document.h"
#include "ui/widgets/drag_merge.h"
#include "ui/common/blob_time.h"
#include "ui/common/status_bar.h"

namespace animorph {

struct BlobInspectorState {
  std::string nameBuffer;  // node name being edited
  int nameNode = -1;
  std::string nameActor;
};

// Draws the node's properties (inside the inspector window). Errors of refused
// edits go to status.
void drawBlobNodeInspector(Document& doc, const std::string& actorId, int nodeId, BlobInspectorState& st,
                           DragMerge& drag, StatusMessage& status);

// Draws the tree-level properties of a BlobTree actor (node count, animation
// length, threshold) inside the inspector window.
void drawBlobActorInspector(Document& doc, const std::string& actorId, DragMerge& drag, StatusMessage& status);

// Draws a key button (a diamond: filled when a key sits at this time, outlined
// when the parameter is animated, grey otherwise); returns true when clicked.
bool keyButton(const char* id, bool keyedHere, bool animated);

}  // namespace animorph
