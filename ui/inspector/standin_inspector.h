#pragma once
// The stand-in section of a morph actor's inspector: its segments listed by
// joint and radius (a click selects one, as in the viewport), and for the
// selected segment its joint (rebind: the segment stays where it is at the
// current frame), radius and ends, with Add, Duplicate, Delete, Refit segment
// and Refit all. Every edit is a command; a drag is one undo step.
#include <string>

#include "core/doc/document.h"
#include "ui/widgets/drag_merge.h"
#include "core/rig/character.h"
#include "ui/viewport/standin_tool.h"
#include "ui/common/status_bar.h"

namespace animorph {

void drawStandinInspector(Document& doc, const Character& c, const std::string& actorId, StandinToolState& st,
                          DragMerge& drag, StatusMessage& status);

// With a joint of a morph actor selected: a button adding a segment on it.
void drawJointStandinButton(Document& doc, const Character& c, const std::string& actorId, int node,
                            StandinToolState& st, StatusMessage& status);

// A new segment on node: from the joint to its first child joint (or a short
// stub along +Y), radius like the stand-in's others. Rest-pose joint space.
StandinSegment newSegmentOnNode(const Character& c, const Standin& s, int node);

}  // namespace animorph
